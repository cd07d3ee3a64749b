//! What kind of emitter a type is: Mitsuba 3.9.1's `EmitterFlags`
//! (`include/mitsuba/render/emitter.h`, same bit values). Each emitter reports them as its
//! plugin's constructor sets `m_flags`; the scene asks which one is the environment and which
//! are reachable only by light sampling.

use bitflags::bitflags;

bitflags! {
    /// A set of Mitsuba `EmitterFlags`.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
    pub struct EmitterFlags: u32 {
        /// Emits from a single point (`point`, `spot`, `projector`).
        const DELTA_POSITION = 0x01;
        /// Emits along a single direction (`directional`).
        const DELTA_DIRECTION = 0x02;
        /// At infinity: the environment and `directional`.
        const INFINITE = 0x04;
        /// Attached to a shape's surface (`area`).
        const SURFACE = 0x08;
        /// Either delta flag.
        const DELTA = Self::DELTA_POSITION.bits() | Self::DELTA_DIRECTION.bits();
    }
}

impl EmitterFlags {
    /// No flag set.
    pub const EMPTY: Self = Self::empty();

    /// Whether any flag of `other` is set.
    #[inline]
    #[must_use]
    pub const fn has(self, other: Self) -> bool {
        self.intersects(other)
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
