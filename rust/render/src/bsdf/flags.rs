//! What kinds of scattering a BSDF has: Mitsuba 3.9.1's `BSDFFlags`
//! (`include/mitsuba/render/bsdf.h`, same bit values), the lobe types and the attributes the
//! renderer and the loader query. Each BSDF reports the union of its lobes' flags as its
//! plugin's constructor sets `m_flags`; a wrapper reports its nested BSDFs' ones.

use bitflags::bitflags;

bitflags! {
    /// A set of Mitsuba `BSDFFlags`.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
    pub struct BsdfFlags: u32 {
        /// A "null" event: the ray continues straight on (`null`, `mask`'s pass-through,
        /// `thindielectric`'s transmission).
        const NULL = 0x00001;
        /// Ideally diffuse reflection.
        const DIFFUSE_REFLECTION = 0x00002;
        /// Ideally diffuse transmission.
        const DIFFUSE_TRANSMISSION = 0x00004;
        /// Glossy reflection.
        const GLOSSY_REFLECTION = 0x00008;
        /// Glossy transmission.
        const GLOSSY_TRANSMISSION = 0x00010;
        /// Reflection into a discrete set of directions (a mirror).
        const DELTA_REFLECTION = 0x00020;
        /// Transmission into a discrete set of directions (smooth refraction).
        const DELTA_TRANSMISSION = 0x00040;
        /// Not symmetric under exchange of the directions (refraction: importance and radiance
        /// transport differ by η²).
        const NON_SYMMETRIC = 0x04000;
        /// Scatters light arriving on the front side.
        const FRONT_SIDE = 0x08000;
        /// Scatters light arriving on the back side.
        const BACK_SIDE = 0x10000;

        /// Any reflection.
        const REFLECTION = Self::DIFFUSE_REFLECTION.bits() | Self::GLOSSY_REFLECTION.bits() | Self::DELTA_REFLECTION.bits();
        /// Any transmission, the null event included (Mitsuba's `Transmission`).
        const TRANSMISSION = Self::DIFFUSE_TRANSMISSION.bits() | Self::GLOSSY_TRANSMISSION.bits() | Self::DELTA_TRANSMISSION.bits() | Self::NULL.bits();
        /// Diffuse scattering.
        const DIFFUSE = Self::DIFFUSE_REFLECTION.bits() | Self::DIFFUSE_TRANSMISSION.bits();
        /// Glossy scattering.
        const GLOSSY = Self::GLOSSY_REFLECTION.bits() | Self::GLOSSY_TRANSMISSION.bits();
        /// Scattering into a 2-D set of directions (has a density: light sampling and MIS apply).
        const SMOOTH = Self::DIFFUSE.bits() | Self::GLOSSY.bits();
        /// Scattering into a discrete set of directions.
        const DELTA = Self::NULL.bits() | Self::DELTA_REFLECTION.bits() | Self::DELTA_TRANSMISSION.bits();

    }
}

impl BsdfFlags {
    /// No flag set.
    pub const EMPTY: Self = Self::empty();

    /// Whether any flag of `other` is set (Mitsuba's `has_flag`).
    #[inline]
    #[must_use]
    pub const fn has(self, other: Self) -> bool {
        self.intersects(other)
    }
}
