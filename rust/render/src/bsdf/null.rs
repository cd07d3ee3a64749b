//! Mitsuba's `null` (`src/bsdfs/null.cpp`): no scattering; a sample continues the ray straight
//! through with weight 1 (a Dirac "null" lobe: no light sampling, no MIS). Like every surface
//! it still blocks shadow rays, as in Mitsuba.

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Mitsuba's `null`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Null;

impl FromProps for Null {
    /// `null` reads no property.
    fn from_props(_p: &mut PluginProps) -> Result<Self, SceneError> {
        Ok(Null)
    }
}

impl Bxdf for Null {
    #[inline]
    fn eval_pdf(&self, _si: &SurfaceInteraction, _wi: Vec3, _wo: Vec3) -> (Vec3, f32) {
        (Vec3::ZERO, 0.0)
    }

    #[inline]
    fn sample(&self, _si: &SurfaceInteraction, wi: Vec3, _u_lobe: f32, _u: Vec2) -> Option<BsdfSample> {
        Some(BsdfSample { wo: -wi, weight: Vec3::ONE, pdf: 1.0, delta: true, eta: 1.0 })
    }

    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::NULL | BsdfFlags::FRONT_SIDE | BsdfFlags::BACK_SIDE
    }
}
