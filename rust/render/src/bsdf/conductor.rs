//! Mitsuba's smooth `conductor` (`src/bsdfs/conductor.cpp`): a one-sided Dirac mirror whose
//! reflectance is the complex-index Fresnel term times `specular_reflectance` (§10).

use super::bxdf::Bxdf;
use super::conductor_ior::conductor_ior_from_props;
use super::flags::BsdfFlags;
use super::fresnel::fresnel_conductor;
use super::parameter_checks::{check_colour, check_finite};
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Smooth conductor. Mitsuba's default `material` "none" (η = 0, k = 1) is a perfect mirror.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor {
    eta: Vec3,
    k: Vec3,
    specular_reflectance: Vec3,
}

impl Conductor {
    /// `eta`/`k`: the complex relative index per RGB channel, e.g. from
    /// [`conductor_material`](super::conductor_ior::conductor_material).
    pub fn new(eta: Vec3, k: Vec3, specular_reflectance: Vec3) -> Result<Self, String> {
        check_finite("conductor", "eta", eta)?;
        check_finite("conductor", "k", k)?;
        check_colour("conductor", "specular_reflectance", specular_reflectance)?;
        Ok(Conductor { eta, k, specular_reflectance })
    }

    /// Mitsuba's `SmoothConductor::sample`: the mirror direction with weight
    /// `specular_reflectance · F(cos θi)`, `pdf` 1, `eta` 1. `None` unless `wi.z > 0`
    /// (one-sided: black from the back). `u_lobe` and `u` are unused.
    #[inline]
    pub fn sample(&self, wi: Vec3, _u_lobe: f32, _u: Vec2) -> Option<BsdfSample> {
        if wi.z.is_nan() || wi.z <= 0.0 {
            return None;
        }
        Some(BsdfSample {
            wo: Vec3::new(-wi.x, -wi.y, wi.z),
            weight: self.specular_reflectance * fresnel_conductor(wi.z, self.eta, self.k),
            pdf: 1.0,
            delta: true,
            eta: 1.0,
        })
    }
}

impl FromProps for Conductor {
    /// `material` or `eta`/`k`, and a constant `specular_reflectance` (default 1).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let (eta, k) = conductor_ior_from_props(p)?;
        Conductor::new(eta, k, p.constant_color("specular_reflectance")?).map_err(|e| p.err(e))
    }
}

impl Bxdf for Conductor {
    #[inline]
    fn eval_pdf(&self, _si: &SurfaceInteraction, _wi: Vec3, _wo: Vec3) -> (Vec3, f32) {
        (Vec3::ZERO, 0.0)
    }

    #[inline]
    fn sample(&self, _si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        Conductor::sample(self, wi, u_lobe, u)
    }

    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DELTA_REFLECTION | BsdfFlags::FRONT_SIDE
    }
}
