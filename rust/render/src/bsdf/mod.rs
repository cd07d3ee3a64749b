//! Renderer-side BSDFs: Mitsuba's `diffuse`, `twosided`, `dielectric`, `thindielectric`,
//! `roughdielectric`, `conductor`, `roughconductor`, `plastic`, `roughplastic`, `normalmap`,
//! `bumpmap`, `mask`, `blendbsdf`, `principled`, `principledthin`, `null`, the matte diffuse
//! kernels and `tabulated_brdf`, all in the local shading frame with Mitsuba's conventions
//! (`eval` returns `f·cos θo`; `wi` points to the previous vertex).
//!
//! One type per plugin, one file each; every type implements [`Bxdf`] and reads its own
//! properties (`from_props`, through `render::load::props::PluginProps`, as Mitsuba's plugin
//! constructors do). [`Bsdf`] is the closed set of them: an enum whose [`Bxdf`] impl
//! forwards to the variant's type (static dispatch), generated from one list below. The trait
//! is in `bxdf.rs`, below every type's file. The wrappers (`twosided`, `mask`, `blendbsdf`,
//! `normalmap`, `bumpmap`) are generic over the BSDF they nest, any [`Bxdf`]: [`Bsdf`] stores
//! `TwoSided<Bsdf>`, `Mask<Bsdf>`, …, whose nested BSDFs the loader builds through
//! `load::props::NestedBsdf`, so that no type's file names the enum.

pub mod blend;
pub mod bump_map;
mod bxdf;
pub mod conductor;
pub mod conductor_ior;
#[allow(clippy::excessive_precision)] // generated data: Mitsuba's values printed in full
mod conductor_ior_data;
pub mod dielectric;
pub mod diffuse;
pub mod flags;
pub mod fresnel;
pub mod mask;
pub mod matte;
pub mod microfacet;
pub mod microfacet_albedo;
pub mod normal_map;
pub mod null;
mod parameter_checks;
pub mod perturbed_frame;
pub mod plastic;
pub mod principled;
pub mod principled_helpers;
pub mod principled_thin;
pub mod rough_conductor;
pub mod rough_dielectric;
pub mod rough_plastic;
pub mod sample;
pub mod thin_dielectric;
pub mod two_sided;
pub mod vndf;

pub use blend::Blend;
pub use bump_map::BumpMap;
pub use bxdf::Bxdf;
pub use conductor::Conductor;
pub use conductor_ior::{conductor_material, conductor_material_names};
pub use dielectric::Dielectric;
pub use diffuse::Diffuse;
pub use flags::BsdfFlags;
pub use fresnel::fresnel_conductor;
pub use mask::Mask;
pub use matte::Matte;
pub use microfacet::MicrofacetDistribution;
pub use normal_map::NormalMap;
pub use null::Null;
pub use plastic::Plastic;
pub use principled::Principled;
pub use principled_thin::PrincipledThin;
pub use rough_conductor::RoughConductor;
pub use rough_dielectric::RoughDielectric;
pub use rough_plastic::RoughPlastic;
pub use sample::BsdfSample;
pub use thin_dielectric::ThinDielectric;
pub use two_sided::TwoSided;

use crate::shape::SurfaceInteraction;
use glam::{Vec2, Vec3};

/// Declares [`Bsdf`] with one variant per BSDF type, its [`Bxdf`] impl (one forwarding
/// match arm per variant and method) and `From` every type.
macro_rules! bsdfs {
    ($($(#[$doc:meta])* $variant:ident($($ty:tt)+)),* $(,)?) => {
        /// One BSDF of the scene: the closed set of renderer BSDF types.
        #[derive(Clone, Debug)]
        pub enum Bsdf {
            $($(#[$doc])* $variant($($ty)+),)*
        }

        impl Bxdf for Bsdf {
            #[inline]
            fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
                match self {
                    $(Bsdf::$variant(b) => <stored_type!($($ty)+) as Bxdf>::eval_pdf(b, si, wi, wo),)*
                }
            }

            #[inline]
            fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
                match self {
                    $(Bsdf::$variant(b) => <stored_type!($($ty)+) as Bxdf>::sample(b, si, wi, u_lobe, u),)*
                }
            }

            #[inline]
            fn flags(&self) -> BsdfFlags {
                match self {
                    $(Bsdf::$variant(b) => <stored_type!($($ty)+) as Bxdf>::flags(b),)*
                }
            }
        }

        $(
            impl From<stored_type!($($ty)+)> for Bsdf {
                #[inline]
                fn from(b: stored_type!($($ty)+)) -> Self {
                    Bsdf::$variant(b.into())
                }
            }
        )*
    };
}

bsdfs! {
    /// `diffuse`.
    Diffuse(Diffuse),
    /// A registered matte diffuse model (`matte_brdf::BSDF_TYPES`).
    Matte(Matte),
    /// `twosided`.
    TwoSided(TwoSided<Bsdf>),
    /// `dielectric`.
    Dielectric(Dielectric),
    /// `conductor`.
    Conductor(Conductor),
    /// `roughconductor`.
    RoughConductor(RoughConductor),
    /// `thindielectric`.
    ThinDielectric(ThinDielectric),
    /// `roughdielectric`.
    RoughDielectric(RoughDielectric),
    /// `plastic`.
    Plastic(Box<Plastic>),
    /// `roughplastic`.
    RoughPlastic(Box<RoughPlastic>),
    /// `normalmap`.
    NormalMap(NormalMap<Bsdf>),
    /// `mask`.
    Mask(Mask<Bsdf>),
    /// `bumpmap`.
    BumpMap(Box<BumpMap<Bsdf>>),
    /// `blendbsdf`.
    Blend(Box<Blend<Bsdf>>),
    /// `principled`.
    Principled(Box<Principled>),
    /// `principledthin`.
    PrincipledThin(Box<PrincipledThin>),
    /// `null`.
    Null(Null),
}
