//! Renderer-side BSDFs: Mitsuba's `diffuse`, `twosided`, `dielectric`, `thindielectric`,
//! `roughdielectric`, `conductor`, `roughconductor`, `plastic`, `roughplastic`, `normalmap`, `bumpmap`, `mask`, `blendbsdf`, `principled`, `principledthin`, `null`, and the matte
//! diffuse kernels, all in the local shading frame with
//! Mitsuba's conventions (`eval` returns `f·cos θo`; `wi` points to the previous vertex).

pub mod blend;
pub mod bump_map;
pub mod conductor;
pub mod conductor_ior;
#[allow(clippy::excessive_precision)] // generated data: Mitsuba's values printed in full
mod conductor_ior_data;
pub mod dielectric;
pub mod diffuse;
pub mod interface;
pub mod mask;
pub mod matte;
pub mod microfacet;
pub mod microfacet_albedo;
pub mod normal_map;
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
pub mod tabulated_brdf;
pub mod textured_roughness;
pub mod thin_dielectric;
pub mod vndf;

pub use blend::Blend;
pub use bump_map::BumpMap;
pub use conductor::Conductor;
pub use conductor_ior::{conductor_material, conductor_material_names};
pub use dielectric::Dielectric;
pub use interface::fresnel_conductor;
pub use mask::Mask;
pub use matte::TexturedMatte;
pub use microfacet::MicrofacetDistribution;
pub use normal_map::NormalMap;
pub use plastic::Plastic;
pub use principled::Principled;
pub use principled_thin::PrincipledThin;
pub use rough_conductor::RoughConductor;
pub use rough_dielectric::RoughDielectric;
pub use rough_plastic::RoughPlastic;
pub use sample::BsdfSample;
pub use tabulated_brdf::TabulatedBrdf;
pub use textured_roughness::{RoughLobe, TexturedRoughness};
pub use thin_dielectric::ThinDielectric;

use crate::render::shape::SurfaceInteraction;
use crate::render::texture::Texture;
use glam::{Vec2, Vec3};

/// One BSDF of the scene.
#[derive(Clone, Debug)]
pub enum Bsdf {
    Diffuse {
        reflectance: Texture,
    },
    Matte {
        model: crate::brdf::DiffuseModel,
        reflectance: Texture,
    },
    /// Mitsuba's `twosided`: `front` for cos θi > 0, `back` (the same BSDF when only one is
    /// nested) for the other side with both directions mirrored.
    TwoSided {
        front: Box<Bsdf>,
        back: Box<Bsdf>,
    },
    Dielectric(Dielectric),
    Conductor(Conductor),
    RoughConductor(RoughConductor),
    ThinDielectric(ThinDielectric),
    RoughDielectric(RoughDielectric),
    Plastic(Box<Plastic>),
    RoughPlastic(Box<RoughPlastic>),
    /// Mitsuba's `normalmap` wrapper around a nested BSDF.
    NormalMap(NormalMap),
    /// Mitsuba's `mask`: the nested BSDF with probability `opacity`, else pass-through.
    Mask(Mask),
    /// Mitsuba's `bumpmap` wrapper around a nested BSDF.
    BumpMap(Box<BumpMap>),
    /// Mitsuba's `blendbsdf`: `(1 − weight)·first + weight·second`.
    Blend(Box<Blend>),
    Principled(Box<Principled>),
    PrincipledThin(Box<PrincipledThin>),
    /// `roughconductor`/`roughdielectric` whose roughness is a texture.
    TexturedRoughness(Box<TexturedRoughness>),
    /// A matte model with textured numeric parameters.
    TexturedMatte(Box<TexturedMatte>),
    /// A BRDF read from a table file (`tabulated_brdf`).
    Tabulated(TabulatedBrdf),
    /// Mitsuba's `null` (`src/bsdfs/null.cpp`): no scattering; a sample continues the ray
    /// straight through with weight 1 (a Dirac "null" lobe: no light sampling, no MIS). Like
    /// every surface it still blocks shadow rays, as in Mitsuba.
    Null,
}

impl Bsdf {
    /// `(f·cos θo, pdf)` for the smooth part (delta lobes contribute nothing here).
    #[inline]
    pub fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        match self {
            Bsdf::Diffuse { reflectance } => diffuse::eval_pdf(reflectance.eval(si), wi, wo),
            Bsdf::Matte { model, reflectance } => matte::eval_pdf(model, reflectance.eval(si), wi, wo),
            Bsdf::Tabulated(t) => tabulated_brdf::eval_pdf(&t.table, t.reflectance.eval(si), wi, wo),
            Bsdf::TwoSided { front, back } => {
                if wi.z > 0.0 {
                    front.eval_pdf(si, wi, wo)
                } else {
                    back.eval_pdf(si, flip(wi), flip(wo))
                }
            }
            Bsdf::Dielectric(_) | Bsdf::Conductor(_) | Bsdf::ThinDielectric(_) | Bsdf::Null => (Vec3::ZERO, 0.0),
            Bsdf::RoughConductor(r) => (r.eval(wi, wo), r.pdf(wi, wo)),
            Bsdf::RoughDielectric(r) => r.eval_pdf(wi, wo),
            Bsdf::Plastic(p) => p.eval_pdf(si, wi, wo),
            Bsdf::RoughPlastic(p) => p.eval_pdf(si, wi, wo),
            Bsdf::NormalMap(n) => n.eval_pdf(si, wi, wo),
            Bsdf::Mask(m) => m.eval_pdf(si, wi, wo),
            Bsdf::Blend(b) => b.eval_pdf(si, wi, wo),
            Bsdf::BumpMap(b) => b.eval_pdf(si, wi, wo),
            Bsdf::Principled(p) => p.eval_pdf(si, wi, wo),
            Bsdf::PrincipledThin(p) => p.eval_pdf(si, wi, wo),
            Bsdf::TexturedRoughness(t) => t.eval_pdf(si, wi, wo),
            Bsdf::TexturedMatte(t) => t.eval_pdf(si, wi, wo),
        }
    }

    /// Samples `wo` from one number for the lobe choice and two for the direction.
    #[inline]
    pub fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        match self {
            Bsdf::Diffuse { reflectance } => diffuse::sample(reflectance.eval(si), wi, u),
            Bsdf::Matte { model, reflectance } => matte::sample(model, reflectance.eval(si), wi, u),
            Bsdf::Tabulated(t) => tabulated_brdf::sample(&t.table, t.reflectance.eval(si), wi, u),
            Bsdf::TwoSided { front, back } => {
                if wi.z > 0.0 {
                    front.sample(si, wi, u_lobe, u)
                } else {
                    let mut s = back.sample(si, flip(wi), u_lobe, u)?;
                    s.wo = flip(s.wo);
                    Some(s)
                }
            }
            Bsdf::Dielectric(d) => d.sample(wi, u_lobe, u),
            Bsdf::Conductor(c) => c.sample(wi, u_lobe, u),
            Bsdf::RoughConductor(r) => r.sample(wi, u_lobe, u),
            Bsdf::ThinDielectric(t) => t.sample(wi, u_lobe, u),
            Bsdf::RoughDielectric(r) => r.sample(wi, u_lobe, u),
            Bsdf::Plastic(p) => p.sample(si, wi, u_lobe, u),
            Bsdf::RoughPlastic(p) => p.sample(si, wi, u_lobe, u),
            Bsdf::NormalMap(n) => n.sample(si, wi, u_lobe, u),
            Bsdf::Mask(m) => m.sample(si, wi, u_lobe, u),
            Bsdf::Blend(b) => b.sample(si, wi, u_lobe, u),
            Bsdf::BumpMap(b) => b.sample(si, wi, u_lobe, u),
            Bsdf::Principled(p) => p.sample(si, wi, u_lobe, u),
            Bsdf::PrincipledThin(p) => p.sample(si, wi, u_lobe, u),
            Bsdf::TexturedRoughness(t) => t.sample(si, wi, u_lobe, u),
            Bsdf::TexturedMatte(t) => t.sample(si, wi, u),
            Bsdf::Null => Some(BsdfSample { wo: -wi, weight: Vec3::ONE, pdf: 1.0, delta: true, eta: 1.0 }),
        }
    }

    /// Whether the BSDF has a non-Dirac component, i.e. whether light sampling is useful
    /// (Mitsuba skips emitter sampling at purely specular surfaces).
    pub fn has_smooth(&self) -> bool {
        match self {
            Bsdf::Diffuse { .. }
            | Bsdf::Matte { .. }
            | Bsdf::Tabulated(_)
            | Bsdf::RoughConductor(_)
            | Bsdf::RoughDielectric(_)
            | Bsdf::Plastic(_)
            | Bsdf::RoughPlastic(_)
            | Bsdf::Principled(_)
            | Bsdf::PrincipledThin(_)
            | Bsdf::TexturedRoughness(_)
            | Bsdf::TexturedMatte(_) => true,
            Bsdf::Dielectric(_) | Bsdf::Conductor(_) | Bsdf::ThinDielectric(_) | Bsdf::Null => false,
            Bsdf::TwoSided { front, back } => front.has_smooth() || back.has_smooth(),
            Bsdf::NormalMap(n) => n.nested.has_smooth(),
            Bsdf::Mask(m) => m.nested.has_smooth(),
            Bsdf::Blend(b) => b.first.has_smooth() || b.second.has_smooth(),
            Bsdf::BumpMap(b) => b.nested.has_smooth(),
        }
    }
}

#[inline]
fn flip(v: Vec3) -> Vec3 {
    Vec3::new(v.x, v.y, -v.z)
}
