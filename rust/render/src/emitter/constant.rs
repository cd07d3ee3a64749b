//! Mitsuba's `constant` emitter (`src/emitters/constant.cpp`): a uniform environment of
//! `radiance` (default 1), sampled uniformly over the sphere. Every Mitsuba emitter reads
//! `to_world` (`src/render/endpoint.cpp`); a uniform environment is invariant under it, so it
//! is validated and ignored.

use super::emitter_sample::EmitterSample;
use super::flags::EmitterFlags;
use super::light::Light;
use crate::geometry::warp;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::{Shape, SurfaceInteraction};
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Uniform environment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Constant {
    pub radiance: Vec3,
}

impl FromProps for Constant {
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        p.transform("to_world")?;
        Ok(Constant { radiance: p.emission("radiance")? })
    }
}

impl Light for Constant {
    #[inline]
    fn flags(&self) -> EmitterFlags {
        EmitterFlags::INFINITE
    }

    #[inline]
    fn sample_direction(&self, ref_p: Vec3, u: Vec2, _shapes: &[Shape]) -> Option<EmitterSample> {
        let d = warp::square_to_uniform_sphere(u);
        let (pdf, dist) = (warp::UNIFORM_SPHERE_PDF, f32::INFINITY);
        Some(EmitterSample { d, dist, pdf, delta: false, weight: self.radiance / pdf, p: ref_p + d, n: -d })
    }

    #[inline]
    fn pdf_direction(&self, _ref_p: Vec3, si: Option<&SurfaceInteraction>, _shapes: &[Shape]) -> f32 {
        if si.is_none() { warp::UNIFORM_SPHERE_PDF } else { 0.0 }
    }

    #[inline]
    fn eval_environment(&self, _d: Vec3) -> Vec3 {
        self.radiance
    }

    #[inline]
    fn pdf_environment(&self, _d: Vec3) -> f32 {
        warp::UNIFORM_SPHERE_PDF
    }
}
