//! What kinds of scattering a BSDF has: Mitsuba 3.9.1's `BSDFFlags`
//! (`include/mitsuba/render/bsdf.h`, same bit values), the lobe types and the attributes the
//! renderer and the loader query. Each BSDF reports the union of its lobes' flags as its
//! plugin's constructor sets `m_flags`; a wrapper reports its nested BSDFs' ones.

use std::ops::{BitAnd, BitOr, BitOrAssign, Not};

/// A set of Mitsuba `BSDFFlags`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct BsdfFlags(u32);

impl BsdfFlags {
    /// No flag set.
    pub const EMPTY: Self = Self(0);
    /// A "null" event: the ray continues straight on (`null`, `mask`'s pass-through,
    /// `thindielectric`'s transmission).
    pub const NULL: Self = Self(0x00001);
    /// Ideally diffuse reflection.
    pub const DIFFUSE_REFLECTION: Self = Self(0x00002);
    /// Ideally diffuse transmission.
    pub const DIFFUSE_TRANSMISSION: Self = Self(0x00004);
    /// Glossy reflection.
    pub const GLOSSY_REFLECTION: Self = Self(0x00008);
    /// Glossy transmission.
    pub const GLOSSY_TRANSMISSION: Self = Self(0x00010);
    /// Reflection into a discrete set of directions (a mirror).
    pub const DELTA_REFLECTION: Self = Self(0x00020);
    /// Transmission into a discrete set of directions (smooth refraction).
    pub const DELTA_TRANSMISSION: Self = Self(0x00040);
    /// Not symmetric under exchange of the directions (refraction: importance and radiance
    /// transport differ by η²).
    pub const NON_SYMMETRIC: Self = Self(0x04000);
    /// Scatters light arriving on the front side.
    pub const FRONT_SIDE: Self = Self(0x08000);
    /// Scatters light arriving on the back side.
    pub const BACK_SIDE: Self = Self(0x10000);

    /// Any reflection.
    pub const REFLECTION: Self =
        Self(Self::DIFFUSE_REFLECTION.0 | Self::GLOSSY_REFLECTION.0 | Self::DELTA_REFLECTION.0);
    /// Any transmission, the null event included (Mitsuba's `Transmission`).
    pub const TRANSMISSION: Self =
        Self(Self::DIFFUSE_TRANSMISSION.0 | Self::GLOSSY_TRANSMISSION.0 | Self::DELTA_TRANSMISSION.0 | Self::NULL.0);
    /// Diffuse scattering.
    pub const DIFFUSE: Self = Self(Self::DIFFUSE_REFLECTION.0 | Self::DIFFUSE_TRANSMISSION.0);
    /// Glossy scattering.
    pub const GLOSSY: Self = Self(Self::GLOSSY_REFLECTION.0 | Self::GLOSSY_TRANSMISSION.0);
    /// Scattering into a 2-D set of directions (has a density: light sampling and MIS apply).
    pub const SMOOTH: Self = Self(Self::DIFFUSE.0 | Self::GLOSSY.0);
    /// Scattering into a discrete set of directions.
    pub const DELTA: Self = Self(Self::NULL.0 | Self::DELTA_REFLECTION.0 | Self::DELTA_TRANSMISSION.0);

    /// Whether any flag of `other` is set (Mitsuba's `has_flag`).
    #[inline]
    #[must_use]
    pub const fn has(self, other: Self) -> bool {
        self.0 & other.0 != 0
    }

    /// The raw bits (Mitsuba's values).
    #[inline]
    #[must_use]
    pub const fn bits(self) -> u32 {
        self.0
    }
}

impl BitOr for BsdfFlags {
    type Output = Self;
    #[inline]
    fn bitor(self, rhs: Self) -> Self {
        Self(self.0 | rhs.0)
    }
}

impl BitOrAssign for BsdfFlags {
    #[inline]
    fn bitor_assign(&mut self, rhs: Self) {
        self.0 |= rhs.0;
    }
}

impl BitAnd for BsdfFlags {
    type Output = Self;
    #[inline]
    fn bitand(self, rhs: Self) -> Self {
        Self(self.0 & rhs.0)
    }
}

impl Not for BsdfFlags {
    type Output = Self;
    #[inline]
    fn not(self) -> Self {
        Self(!self.0)
    }
}
