//! Wolff (JOSA A 11(11), 1994): diffuse reflection from a smooth dielectric. Light is Fresnel
//! transmitted into the body at θi, scattered into an isotropic internal distribution and
//! transmitted out towards the viewer. As a BRDF (research page §3b):
//!
//! `f = K · T(θi) · T(θo)`, `T(θ) = 1 − F(θ, n)`, n = int_ior / ext_ior,
//!
//! using the Stokes identity `1 − F(asin(sin θo / n), 1/n) = 1 − F(θo, n)` so that the exit
//! term needs no refraction (and the form is visibly reciprocal). The seed paper's radiance
//! form carries `cos θi`, which is the renderer's, not the kernel's.
//!
//! `K` is Wolff's lumped constant; matte offers the three choices of §3c:
//! * `physical` (default): `ρ / (π n² (1 − ρ F_dr,int))`: isotropic internal radiance with all
//!   internally reflected light re-scattered (Mitsuba 0.6 `plastic` diffuse lobe, nonlinear);
//!   ρ is the internal single-bounce albedo; albedo `(1 − F(θi)) ρ(1−F_dr,int)/(1−ρF_dr,int)`.
//! * `normal`: `ρ / (π (1 − F(0)) (1 − F_dr,ext))`, scaled so that E(0°) = ρ (same albedo as
//!   Lambert at normal incidence; the fair side-by-side comparison).
//! * `raw`: `ρ / π`.

use super::fresnel::{Transmittance, diffuse_fresnel_reflectance, fresnel_dielectric};
use super::frame::both_above;
use super::model::{Albedo, AlbedoMethod, DiffuseBrdf};
use super::params::{ParamError, Params};
use glam::Vec3;
use std::f64::consts::PI;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WolffNormalization {
    Physical,
    Normal,
    Raw,
}

impl WolffNormalization {
    pub fn as_str(self) -> &'static str {
        match self {
            WolffNormalization::Physical => "physical",
            WolffNormalization::Normal => "normal",
            WolffNormalization::Raw => "raw",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wolff {
    int_ior: f32,
    ext_ior: f32,
    /// Relative index `n = int_ior / ext_ior`.
    eta: f32,
    normalization: WolffNormalization,
    /// `F_dr,ext(n)`: cosine-weighted hemispherical Fresnel reflectance seen from outside.
    f_dr_ext: f32,
    /// `F_dr,int = F_dr(1/n)`: the same seen from inside (includes total internal reflection).
    f_dr_int: f32,
    /// The per-eval transmittance `1 − F(θ, n)`.
    transmittance: Transmittance,
    /// The part of K that does not depend on ρ: `1/π` (raw), `1/(π (1 − F(0)) (1 − F_dr,ext))`
    /// (normal), `1/(π n²)` (physical), computed in f64 so each eval multiplies once.
    k_scale: f32,
}

impl Wolff {
    pub const DEFAULT_INT_IOR: f64 = 1.4;
    pub const DEFAULT_EXT_IOR: f64 = 1.0;

    pub fn new(int_ior: f64, ext_ior: f64, normalization: WolffNormalization) -> Result<Self, ParamError> {
        if !(int_ior >= 1.0) || !int_ior.is_finite() {
            return Err(ParamError::new("int_ior", format!("must be a finite index of refraction >= 1 (got {int_ior})")));
        }
        if !(ext_ior >= 1.0) || !ext_ior.is_finite() {
            return Err(ParamError::new("ext_ior", format!("must be a finite index of refraction >= 1 (got {ext_ior})")));
        }
        let eta = int_ior / ext_ior;
        if eta < 1.0 {
            return Err(ParamError::new(
                "int_ior",
                format!("must be >= ext_ior: Wolff's model is a denser body under a smooth interface (got int_ior {int_ior} < ext_ior {ext_ior})"),
            ));
        }
        let f_dr_ext = diffuse_fresnel_reflectance(eta);
        let f0 = fresnel_dielectric(1.0, eta);
        let k_scale = match normalization {
            WolffNormalization::Raw => 1.0 / PI,
            WolffNormalization::Normal => 1.0 / (PI * (1.0 - f0) * (1.0 - f_dr_ext)),
            WolffNormalization::Physical => 1.0 / (PI * eta * eta),
        };
        Ok(Self {
            int_ior: int_ior as f32,
            ext_ior: ext_ior as f32,
            eta: eta as f32,
            normalization,
            f_dr_ext: f_dr_ext as f32,
            f_dr_int: diffuse_fresnel_reflectance(1.0 / eta) as f32,
            transmittance: Transmittance::new(eta),
            k_scale: k_scale as f32,
        })
    }

    pub fn from_params(p: &mut Params) -> Result<Self, ParamError> {
        let int_ior = p.ior("int_ior", Self::DEFAULT_INT_IOR)?;
        let ext_ior = p.ior("ext_ior", Self::DEFAULT_EXT_IOR)?;
        let normalization = match p.choice("normalization", &["physical", "normal", "raw"], "physical")? {
            "normal" => WolffNormalization::Normal,
            "raw" => WolffNormalization::Raw,
            _ => WolffNormalization::Physical,
        };
        Self::new(int_ior, ext_ior, normalization)
    }

    pub fn int_ior(&self) -> f32 {
        self.int_ior
    }
    pub fn ext_ior(&self) -> f32 {
        self.ext_ior
    }
    pub fn normalization(&self) -> WolffNormalization {
        self.normalization
    }

    /// The constant K for one reflectance channel. ρ is clamped to [0, 1] for `physical`,
    /// whose geometric series diverges at ρ = 1/F_dr,int.
    #[inline]
    fn k(&self, rho: f32) -> f32 {
        match self.normalization {
            WolffNormalization::Raw | WolffNormalization::Normal => rho * self.k_scale,
            WolffNormalization::Physical => {
                let rho = rho.clamp(0.0, 1.0);
                rho * self.k_scale / (1.0 - rho * self.f_dr_int)
            }
        }
    }
}

impl DiffuseBrdf for Wolff {
    #[inline]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        if !both_above(wi, wo) {
            return [0.0; N];
        }
        let t = self.transmittance.at(wi.z) * self.transmittance.at(wo.z);
        reflectance.map(|rho| self.k(rho) * t)
    }

    /// `E(θi) = K T(θi) π (1 − F_dr,ext)`, since `∫ T(θo) cos θo dωo = π (1 − F_dr,ext)`.
    fn albedo(&self, cos_theta_i: f64, reflectance: f32) -> Albedo {
        let value = if cos_theta_i <= 0.0 {
            0.0
        } else {
            let t_i = 1.0 - fresnel_dielectric(cos_theta_i, self.eta as f64);
            self.k(reflectance) as f64 * t_i * PI * (1.0 - self.f_dr_ext as f64)
        };
        Albedo { value, method: AlbedoMethod::ClosedForm }
    }
}
