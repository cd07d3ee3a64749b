//! Mitsuba's smooth `dielectric` (`src/bsdfs/dielectric.cpp`): a glass interface with one
//! Dirac reflection and one Dirac refraction lobe, the lobe chosen with probability Fresnel R
//! (docs/renderer-semantics.md §10). Two-sided: the interior is the side opposite the normal.

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::fresnel::fresnel_dielectric;
use super::parameter_checks::check_colour;
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Smooth dielectric interface (radiance transport).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric {
    /// η = int_ior / ext_ior, computed in f32 as Mitsuba does.
    eta: f32,
    specular_reflectance: Vec3,
    specular_transmittance: Vec3,
}

impl Dielectric {
    /// `int_ior`/`ext_ior` are the interior/exterior indices (named ones resolved by the caller
    /// with `brdf::params::lookup_ior`; Mitsuba's defaults are bk7 = 1.5046 and air =
    /// 1.000277). Both must be finite and positive, the colours finite and non-negative.
    pub fn new(
        int_ior: f32,
        ext_ior: f32,
        specular_reflectance: Vec3,
        specular_transmittance: Vec3,
    ) -> Result<Self, String> {
        for (name, v) in [("int_ior", int_ior), ("ext_ior", ext_ior)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("dielectric: {name} must be a positive finite number, got {v}"));
            }
        }
        check_colour("dielectric", "specular_reflectance", specular_reflectance)?;
        check_colour("dielectric", "specular_transmittance", specular_transmittance)?;
        let eta = int_ior / ext_ior;
        if !(eta.is_finite() && eta > 0.0) {
            return Err(format!("dielectric: int_ior/ext_ior = {int_ior}/{ext_ior} is not a usable relative index"));
        }
        Ok(Dielectric { eta, specular_reflectance, specular_transmittance })
    }

    /// Relative index of refraction η = int_ior / ext_ior.
    pub fn eta(&self) -> f32 {
        self.eta
    }

    /// Mitsuba's `SmoothDielectric::sample` in radiance mode (`u` is unused, as there).
    /// Reflects if `u_lobe ≤ R` (weight `specular_reflectance`, `pdf` = R, `eta` = 1), else
    /// refracts (weight `specular_transmittance · (η_i/η_t)²`, `pdf` = 1 − R, `eta` = η_t/η_i).
    /// The 1/pdf of the lobe choice cancels the Fresnel factor, so neither appears in the
    /// weight. Always `Some` for a unit `wi`; at `wi.z = 0` it reflects (R = 1).
    #[inline]
    pub fn sample(&self, wi: Vec3, u_lobe: f32, _u: Vec2) -> Option<BsdfSample> {
        let f = fresnel_dielectric(wi.z, self.eta);
        // `r >= 1` also keeps TIR on the reflection lobe for an out-of-range `u_lobe`.
        if u_lobe <= f.r || f.r >= 1.0 {
            Some(BsdfSample {
                wo: Vec3::new(-wi.x, -wi.y, wi.z),
                weight: self.specular_reflectance,
                pdf: f.r,
                delta: true,
                eta: 1.0,
            })
        } else {
            // The tangential component scales by η_i/η_t (Snell), the normal one is cos θt.
            Some(BsdfSample {
                wo: Vec3::new(-f.eta_ti * wi.x, -f.eta_ti * wi.y, f.cos_t),
                // Radiance is compressed into a smaller solid angle entering the denser side.
                weight: self.specular_transmittance * (f.eta_ti * f.eta_ti),
                pdf: 1.0 - f.r,
                delta: true,
                eta: f.eta_it,
            })
        }
    }
}

impl FromProps for Dielectric {
    /// `int_ior`, `ext_ior` (numbers or names; bk7 over air) and constant `specular_*`
    /// weights (default 1).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let int_ior = p.ior("int_ior")?;
        let ext_ior = p.ior("ext_ior")?;
        let r = p.constant_color("specular_reflectance")?;
        let t = p.constant_color("specular_transmittance")?;
        Dielectric::new(int_ior, ext_ior, r, t).map_err(|e| p.err(e))
    }
}

impl Bxdf for Dielectric {
    #[inline]
    fn eval_pdf(&self, _si: &SurfaceInteraction, _wi: Vec3, _wo: Vec3) -> (Vec3, f32) {
        (Vec3::ZERO, 0.0)
    }

    #[inline]
    fn sample(&self, _si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        Dielectric::sample(self, wi, u_lobe, u)
    }

    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DELTA_REFLECTION
            | BsdfFlags::DELTA_TRANSMISSION
            | BsdfFlags::NON_SYMMETRIC
            | BsdfFlags::FRONT_SIDE
            | BsdfFlags::BACK_SIDE
    }
}
