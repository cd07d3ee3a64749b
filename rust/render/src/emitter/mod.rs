//! Emitters (Mitsuba `src/emitters/*.cpp`, docs/renderer-semantics.md §9), one type per plugin
//! and file: [`Area`] (one-sided w.r.t. the shading normal, attached to a shape), [`Point`],
//! [`Spot`], [`Projector`], [`Directional`], and the [`Constant`] and [`EnvMap`] environments.
//! Radiance values are linear RGB.
//!
//! Every type implements [`Light`] (pbrt-v4's name; Mitsuba's `Emitter` interface) and reads
//! its own properties (`from_props`, through `render::load::props::PluginProps`, as Mitsuba's
//! plugin constructors do). [`Emitter`] is the closed set of them: an enum whose [`Light`]
//! impl forwards to the variant's type (static dispatch), generated from one list below, as
//! [`crate::bsdf::Bsdf`] is. The trait is in `light.rs`, below every type's file.

pub mod area;
pub mod constant;
pub mod directional;
pub mod emitter_sample;
pub mod envmap;
pub mod flags;
mod light;
pub mod point;
pub mod projector;
pub mod spot;

pub use area::Area;
pub use constant::Constant;
pub use directional::Directional;
pub use emitter_sample::{EmitterPosition, EmitterSample, LightRay};
pub use envmap::EnvMap;
pub use flags::EmitterFlags;
pub use light::Light;
pub use point::Point;
pub use projector::Projector;
pub use spot::Spot;

use crate::shape::{Shape, SurfaceInteraction};
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// Declares [`Emitter`] with one variant per emitter type, its [`Light`] impl (one forwarding
/// match arm per variant and method) and `From` every type.
macro_rules! emitters {
    ($($(#[$doc:meta])* $variant:ident($($ty:tt)+)),* $(,)?) => {
        /// One emitter of the scene: the closed set of emitter types.
        #[derive(Clone, Debug)]
        pub enum Emitter {
            $($(#[$doc])* $variant($($ty)+),)*
        }

        impl Light for Emitter {
            #[inline]
            fn flags(&self) -> EmitterFlags {
                match self {
                    $(Emitter::$variant(e) => <stored_type!($($ty)+) as Light>::flags(e),)*
                }
            }

            #[inline]
            fn sample_direction(&self, ref_p: Vec3, u: Vec2, shapes: &[Shape]) -> Option<EmitterSample> {
                match self {
                    $(Emitter::$variant(e) => <stored_type!($($ty)+) as Light>::sample_direction(e, ref_p, u, shapes),)*
                }
            }

            #[inline]
            fn pdf_direction(&self, ref_p: Vec3, si: Option<&SurfaceInteraction>, shapes: &[Shape]) -> f32 {
                match self {
                    $(Emitter::$variant(e) => <stored_type!($($ty)+) as Light>::pdf_direction(e, ref_p, si, shapes),)*
                }
            }

            #[inline]
            fn eval_surface(&self, si: &SurfaceInteraction) -> Vec3 {
                match self {
                    $(Emitter::$variant(e) => <stored_type!($($ty)+) as Light>::eval_surface(e, si),)*
                }
            }

            #[inline]
            fn eval_environment(&self, d: Vec3) -> Vec3 {
                match self {
                    $(Emitter::$variant(e) => <stored_type!($($ty)+) as Light>::eval_environment(e, d),)*
                }
            }

            #[inline]
            fn pdf_environment(&self, d: Vec3) -> f32 {
                match self {
                    $(Emitter::$variant(e) => <stored_type!($($ty)+) as Light>::pdf_environment(e, d),)*
                }
            }

            #[inline]
            fn can_sample_ray(&self, shapes: &[Shape]) -> bool {
                match self {
                    $(Emitter::$variant(e) => <stored_type!($($ty)+) as Light>::can_sample_ray(e, shapes),)*
                }
            }

            #[inline]
            fn sample_position(&self, u: Vec2, shapes: &[Shape]) -> Option<EmitterPosition> {
                match self {
                    $(Emitter::$variant(e) => <stored_type!($($ty)+) as Light>::sample_position(e, u, shapes),)*
                }
            }

            #[inline]
            fn sample_ray(&self, u_pos: Vec2, u_dir: Vec2, shapes: &[Shape]) -> Option<LightRay> {
                match self {
                    $(Emitter::$variant(e) => <stored_type!($($ty)+) as Light>::sample_ray(e, u_pos, u_dir, shapes),)*
                }
            }
        }

        $(
            impl From<stored_type!($($ty)+)> for Emitter {
                #[inline]
                fn from(e: stored_type!($($ty)+)) -> Self {
                    Emitter::$variant(e.into())
                }
            }
        )*
    };
}

emitters! {
    /// `area`.
    Area(Area),
    /// `point`.
    Point(Point),
    /// `spot`.
    Spot(Spot),
    /// `directional`.
    Directional(Directional),
    /// `constant`.
    Constant(Constant),
    /// `projector`.
    Projector(Projector),
    /// `envmap` (shared: its image and sampling tables are large).
    EnvMap(Arc<EnvMap>),
}

impl Emitter {
    /// Point, spot, projector and directional lights: reachable only by light sampling.
    #[inline]
    #[must_use]
    pub fn is_delta(&self) -> bool {
        self.flags().is_delta()
    }

    /// Whether this is the scene's environment (`constant` or `envmap`).
    #[inline]
    #[must_use]
    pub fn is_environment(&self) -> bool {
        self.flags().is_environment()
    }

    /// The shape an `area` emitter is attached to.
    #[must_use]
    pub fn area_shape(&self) -> Option<u32> {
        match self {
            Emitter::Area(a) => Some(a.shape),
            _ => None,
        }
    }
}
