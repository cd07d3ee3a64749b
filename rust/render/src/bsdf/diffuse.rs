//! Mitsuba's built-in `diffuse` (`src/bsdfs/diffuse.cpp`): ρ/π, one-sided (zero when either
//! direction is below the shading surface), cosine-weighted sampling with weight ρ.

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_brdf::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use matte_scene_file::SceneError;
use std::f32::consts::FRAC_1_PI;

/// Mitsuba's `diffuse`: `reflectance` ρ (a texture, default 0.5).
#[derive(Clone, Debug)]
pub struct Diffuse {
    pub reflectance: Texture,
}

impl FromProps for Diffuse {
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        Ok(Diffuse { reflectance: p.texture("reflectance")? })
    }
}

impl Bxdf for Diffuse {
    /// `(ρ/π·cos θo, cos θo/π)`.
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        (self.reflectance.eval(si) * (FRAC_1_PI * wo.z), cosine_hemisphere_pdf(wo))
    }

    /// A cosine-weighted direction, weight ρ.
    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, _u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wi.z <= 0.0 {
            return None;
        }
        let wo = square_to_cosine_hemisphere(u);
        let pdf = cosine_hemisphere_pdf(wo);
        if !(pdf > 0.0) || wo.z <= 0.0 {
            return None;
        }
        Some(BsdfSample { wo, weight: self.reflectance.eval(si), pdf, delta: false, eta: 1.0 })
    }

    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DIFFUSE_REFLECTION | BsdfFlags::FRONT_SIDE
    }
}
