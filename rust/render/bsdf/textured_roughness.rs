//! `roughconductor` / `roughdielectric` with a texture for `alpha`, `alpha_u` or `alpha_v`
//! (Mitsuba reads them with `get_unbounded_texture` and builds the microfacet distribution
//! from their `eval_1` at every hit: `src/bsdfs/roughconductor.cpp`, `roughdielectric.cpp`).
//! The lobe is stored with its constant parameters; per hit it is copied with the textures'
//! roughness (raised to 1e-4 as in Mitsuba).

use super::rough_conductor::RoughConductor;
use super::rough_dielectric::RoughDielectric;
use super::sample::BsdfSample;
use crate::render::shape::SurfaceInteraction;
use crate::render::texture::Texture;
use glam::{Vec2, Vec3};

#[derive(Clone, Debug)]
pub enum RoughLobe {
    Conductor(RoughConductor),
    Dielectric(RoughDielectric),
}

#[derive(Clone, Debug)]
pub struct TexturedRoughness {
    pub alpha_u: Texture,
    pub alpha_v: Texture,
    pub lobe: RoughLobe,
}

impl TexturedRoughness {
    /// The lobe with the roughness at the hit.
    #[inline]
    fn at(&self, si: &SurfaceInteraction) -> RoughLobe {
        let (au, av) = (self.alpha_u.eval_1(si), self.alpha_v.eval_1(si));
        match &self.lobe {
            RoughLobe::Conductor(c) => RoughLobe::Conductor(c.with_alpha(au, av)),
            RoughLobe::Dielectric(d) => RoughLobe::Dielectric(d.with_alpha(au, av)),
        }
    }

    #[inline]
    pub fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        match self.at(si) {
            RoughLobe::Conductor(c) => (c.eval(wi, wo), c.pdf(wi, wo)),
            RoughLobe::Dielectric(d) => d.eval_pdf(wi, wo),
        }
    }

    #[inline]
    pub fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        match self.at(si) {
            RoughLobe::Conductor(c) => c.sample(wi, u_lobe, u),
            RoughLobe::Dielectric(d) => d.sample(wi, u_lobe, u),
        }
    }
}
