//! What kind of emitter a type is: Mitsuba 3.9.1's `EmitterFlags`
//! (`include/mitsuba/render/emitter.h`, same bit values). Each emitter reports them as its
//! plugin's constructor sets `m_flags`; the scene asks which one is the environment and which
//! are reachable only by light sampling.

use std::ops::BitOr;

/// A set of Mitsuba `EmitterFlags`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct EmitterFlags(u32);

impl EmitterFlags {
    /// No flag set.
    pub const EMPTY: Self = Self(0);
    /// Emits from a single point (`point`, `spot`, `projector`).
    pub const DELTA_POSITION: Self = Self(0x01);
    /// Emits along a single direction (`directional`).
    pub const DELTA_DIRECTION: Self = Self(0x02);
    /// At infinity: the environment and `directional`.
    pub const INFINITE: Self = Self(0x04);
    /// Attached to a shape's surface (`area`).
    pub const SURFACE: Self = Self(0x08);
    /// Either delta flag.
    pub const DELTA: Self = Self(Self::DELTA_POSITION.0 | Self::DELTA_DIRECTION.0);

    /// Whether any flag of `other` is set.
    #[inline]
    #[must_use]
    pub const fn has(self, other: Self) -> bool {
        self.0 & other.0 != 0
    }

    /// Reachable only by light sampling (a delta position or direction).
    #[inline]
    #[must_use]
    pub const fn is_delta(self) -> bool {
        self.has(Self::DELTA)
    }

    /// The scene's environment: at infinity and not delta (`constant`, `envmap`).
    #[inline]
    #[must_use]
    pub const fn is_environment(self) -> bool {
        self.has(Self::INFINITE) && !self.is_delta()
    }
}

impl BitOr for EmitterFlags {
    type Output = Self;

    #[inline]
    fn bitor(self, rhs: Self) -> Self {
        Self(self.0 | rhs.0)
    }
}
