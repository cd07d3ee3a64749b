//! Mitsuba's `thindielectric` (`src/bsdfs/thindielectric.cpp`, v3.9.1): a thin pane of glass
//! with infinitely many internal bounces summed in closed form. With R = Fresnel(|cos θi|, η),
//! the pane reflects R' = 2R/(1 + R) (Dirac mirror) and passes 1 − R' straight through
//! (`wo = −wi`, Mitsuba's "null" lobe: no refraction, no η change). Two-sided; no smooth part.

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::fresnel::fresnel_dielectric;
use super::parameter_checks::check_colour;
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Mitsuba's `thindielectric`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinDielectric {
    eta: f32,
    specular_reflectance: Vec3,
    specular_transmittance: Vec3,
}

impl ThinDielectric {
    /// `eta` = int_ior/ext_ior (Mitsuba's defaults: bk7 over air). Absent colours are 1.
    pub fn new(eta: f32, specular_reflectance: Vec3, specular_transmittance: Vec3) -> Result<Self, String> {
        if !(eta.is_finite() && eta > 0.0) {
            return Err(format!("thindielectric: int_ior/ext_ior must be a positive finite ratio, got {eta}"));
        }
        check_colour("thindielectric", "specular_reflectance", specular_reflectance)?;
        check_colour("thindielectric", "specular_transmittance", specular_transmittance)?;
        Ok(ThinDielectric { eta, specular_reflectance, specular_transmittance })
    }

    /// The pane's total reflectance R' = 2R/(1 + R) at `cos_i` (either side).
    #[inline]
    pub fn reflectance(&self, cos_i: f32) -> f32 {
        let r = fresnel_dielectric(cos_i.abs(), self.eta).r;
        r * 2.0 / (1.0 + r)
    }

    /// Reflects if `u_lobe ≤ R'` (weight `specular_reflectance`, pdf R'), else passes through
    /// (weight `specular_transmittance`, pdf 1 − R'); both Dirac, `eta` 1.
    #[inline]
    pub fn sample(&self, wi: Vec3, u_lobe: f32, _u: Vec2) -> Option<BsdfSample> {
        if !wi.is_finite() {
            return None;
        }
        let r = self.reflectance(wi.z);
        if u_lobe <= r {
            Some(BsdfSample {
                wo: Vec3::new(-wi.x, -wi.y, wi.z),
                weight: self.specular_reflectance,
                pdf: r,
                delta: true,
                eta: 1.0,
            })
        } else {
            Some(BsdfSample { wo: -wi, weight: self.specular_transmittance, pdf: 1.0 - r, delta: true, eta: 1.0 })
        }
    }
}

impl FromProps for ThinDielectric {
    /// `int_ior`, `ext_ior` (numbers or names; bk7 over air) and constant `specular_*`
    /// weights (default 1).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let eta = p.ior("int_ior")? / p.ior("ext_ior")?;
        let r = p.constant_color("specular_reflectance")?;
        let t = p.constant_color("specular_transmittance")?;
        ThinDielectric::new(eta, r, t).map_err(|e| p.err(e))
    }
}

impl Bxdf for ThinDielectric {
    #[inline]
    fn eval_pdf(&self, _si: &SurfaceInteraction, _wi: Vec3, _wo: Vec3) -> (Vec3, f32) {
        (Vec3::ZERO, 0.0)
    }

    #[inline]
    fn sample(&self, _si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        ThinDielectric::sample(self, wi, u_lobe, u)
    }

    /// The pass-through is Mitsuba's null event (no refraction).
    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DELTA_REFLECTION | BsdfFlags::NULL | BsdfFlags::FRONT_SIDE | BsdfFlags::BACK_SIDE
    }
}
