//! Mitsuba's smooth `plastic` (`src/bsdfs/plastic.cpp`, v3.9.1): a diffuse base under a smooth
//! dielectric coating. One Dirac reflection lobe (Fresnel R(θi), optionally tinted by
//! `specular_reflectance`) and a diffuse lobe
//!
//! ```text
//! f·cos θo = ρ' · cos θo/π · (1 − R(θi)) (1 − R(θo)) / η²,   ρ' = ρ / (1 − F_dr,int)
//! ```
//!
//! with `nonlinear` = true giving ρ' = ρ / (1 − ρ·F_dr,int) instead. F_dr,int is Mitsuba's
//! fitted diffuse Fresnel reflectance of the inner side, `fresnel_diffuse_reflectance(1/η)`.
//! One-sided (black unless both directions are above the surface).
//!
//! Sampling picks the mirror with probability p_s ∝ R(θi)·w, the diffuse lobe with
//! p_d ∝ (1 − R(θi))·(1 − w), where w = mean(specular)/(mean(diffuse) + mean(specular)) (the
//! textures' `mean()`), then draws a cosine-weighted direction. The diffuse pdf is
//! p_d·cos θo/π.

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::fresnel::fresnel_dielectric;
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_brdf::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use matte_scene_file::SceneError;

/// Smooth plastic.
#[derive(Clone, Debug)]
pub struct Plastic {
    eta: f32,
    inv_eta_2: f32,
    fdr_int: f32,
    diffuse: Texture,
    /// `None` when the XML has no `specular_reflectance` (Mitsuba then skips the product).
    specular: Option<Vec3>,
    specular_sampling_weight: f32,
    nonlinear: bool,
}

/// Mitsuba's `fresnel_diffuse_reflectance(eta)` (`include/mitsuba/render/fresnel.h`): the
/// hemispherical average of Fresnel R, from Egan & Hilgeman's fit for η < 1 and d'Eon &
/// Irving's polynomial in 1/η otherwise. A fit, not an integral, so matte uses the same fit.
pub fn fresnel_diffuse_reflectance(eta: f32) -> f32 {
    let inv = 1.0 / eta;
    if eta < 1.0 {
        0.0636f32.mul_add(inv, eta.mul_add(eta.mul_add(-1.4399, 0.7099), 0.6681))
    } else {
        let c = [0.919317f32, -3.4793, 6.75335, -7.80989, 4.98554, -1.36881];
        c.iter().rev().fold(0.0f32, |acc, &ci| acc.mul_add(inv, ci))
    }
}

impl FromProps for Plastic {
    /// `int_ior`/`ext_ior` (polypropylene over air), `diffuse_reflectance` (a texture, default
    /// 0.5), a constant `specular_reflectance` if given, `nonlinear` (default false).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let eta = p.ior("int_ior")? / p.ior("ext_ior")?;
        let diffuse = p.texture("diffuse_reflectance")?;
        let specular = p.optional_constant_color("specular_reflectance")?;
        let nonlinear = p.boolean("nonlinear")?;
        Plastic::new(eta, diffuse, specular, nonlinear).map_err(|e| p.err(e))
    }
}

impl Plastic {
    /// `eta` = int_ior/ext_ior (> 0, finite; Mitsuba's defaults are polypropylene 1.49 over air
    /// 1.000277). `specular` is `specular_reflectance` if given.
    pub fn new(eta: f32, diffuse: Texture, specular: Option<Vec3>, nonlinear: bool) -> Result<Self, String> {
        if !(eta.is_finite() && eta > 0.0) {
            return Err(format!("plastic: int_ior/ext_ior must be a positive finite ratio, got {eta}"));
        }
        if let Some(s) = specular {
            super::parameter_checks::check_colour("plastic", "specular_reflectance", s)?;
        }
        let s_mean = specular.map_or(1.0, |s| (s.x + s.y + s.z) / 3.0);
        let d_mean = diffuse.mean();
        let w = s_mean / (d_mean + s_mean);
        Ok(Plastic {
            eta,
            inv_eta_2: 1.0 / (eta * eta),
            fdr_int: fresnel_diffuse_reflectance(1.0 / eta),
            diffuse,
            specular,
            specular_sampling_weight: w,
            nonlinear,
        })
    }

    /// The precomputed lobe-selection weight (for tests).
    pub fn specular_sampling_weight(&self) -> f32 {
        self.specular_sampling_weight
    }

    /// ρ/(1 − F_dr) or ρ/(1 − ρ F_dr).
    #[inline]
    fn diffuse_albedo(&self, si: &SurfaceInteraction) -> Vec3 {
        let d = self.diffuse.eval(si);
        if self.nonlinear { d / (Vec3::ONE - d * self.fdr_int) } else { d / (1.0 - self.fdr_int) }
    }

    /// Unnormalised lobe weights (specular, diffuse) given R(θi).
    #[inline]
    fn lobe_weights(&self, f_i: f32) -> (f32, f32) {
        let w = self.specular_sampling_weight;
        (f_i * w, (1.0 - f_i) * (1.0 - w))
    }
}

impl Bxdf for Plastic {
    /// `(f·cos θo, pdf)` of the diffuse lobe (the mirror has no density).
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return (Vec3::ZERO, 0.0);
        }
        let f_i = fresnel_dielectric(wi.z, self.eta).r;
        let f_o = fresnel_dielectric(wo.z, self.eta).r;
        let hemi = cosine_hemisphere_pdf(wo);
        let f = self.diffuse_albedo(si) * (hemi * self.inv_eta_2 * (1.0 - f_i) * (1.0 - f_o));
        let (ps, pd) = self.lobe_weights(f_i);
        (f, hemi * (pd / (ps + pd)))
    }

    /// Mirror if `u_lobe < p_s` (weight R/p_s·specular, pdf p_s, Dirac), else a cosine-weighted
    /// direction from `u`.
    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if !(wi.z > 0.0) {
            return None;
        }
        let f_i = fresnel_dielectric(wi.z, self.eta).r;
        // As Mitsuba's `sample`: normalise p_s, and p_d = 1 − p_s.
        let (ps, pd) = self.lobe_weights(f_i);
        let prob_specular = ps / (ps + pd);
        let prob_diffuse = 1.0 - prob_specular;
        if u_lobe < prob_specular {
            let weight = self.specular.unwrap_or(Vec3::ONE) * (f_i / prob_specular);
            return Some(BsdfSample {
                wo: Vec3::new(-wi.x, -wi.y, wi.z),
                weight,
                pdf: prob_specular,
                delta: true,
                eta: 1.0,
            });
        }
        let wo = square_to_cosine_hemisphere(u);
        let pdf = prob_diffuse * cosine_hemisphere_pdf(wo);
        if !(pdf > 0.0 && wo.z > 0.0) {
            return None;
        }
        let f_o = fresnel_dielectric(wo.z, self.eta).r;
        let weight = self.diffuse_albedo(si) * (self.inv_eta_2 * (1.0 - f_i) * (1.0 - f_o) / prob_diffuse);
        Some(BsdfSample { wo, weight, pdf, delta: false, eta: 1.0 })
    }

    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DELTA_REFLECTION | BsdfFlags::DIFFUSE_REFLECTION | BsdfFlags::FRONT_SIDE
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// F_dr = 2∫₀¹ R(μ) μ dμ from the f64 Fresnel formula (light from the side of index 1 into
    /// index η; TIR counts as R = 1), by a fine midpoint rule.
    fn f_dr(eta: f64) -> f64 {
        let n = 200_000;
        let mut sum = 0.0;
        for k in 0..n {
            let mu = (k as f64 + 0.5) / n as f64;
            let sin_t2 = (1.0 - mu * mu) / (eta * eta);
            let r = if sin_t2 >= 1.0 {
                1.0
            } else {
                let ct = (1.0 - sin_t2).sqrt();
                let rs = (mu - eta * ct) / (mu + eta * ct);
                let rp = (eta * mu - ct) / (eta * mu + ct);
                0.5 * (rs * rs + rp * rp)
            };
            sum += r * mu;
        }
        2.0 * sum / n as f64
    }

    /// The fits are within their published accuracy of the integral (d'Eon & Irving: 0.1 %
    /// for η ∈ [1, 2]; Egan & Hilgeman for the inner side, a few tenths of a percent).
    #[test]
    fn diffuse_fresnel_fit_matches_the_integral() {
        for eta in [1.2f64, 1.49, 1.9] {
            let (fit, exact) = (fresnel_diffuse_reflectance(eta as f32) as f64, f_dr(eta));
            assert!((fit - exact).abs() < 2e-3 * exact, "η {eta}: fit {fit}, integral {exact}");
        }
        for eta in [1.33f64, 1.5] {
            let (fit, exact) = (fresnel_diffuse_reflectance((1.0 / eta) as f32) as f64, f_dr(1.0 / eta));
            assert!((fit - exact).abs() < 1e-2 * exact, "1/η = 1/{eta}: fit {fit}, integral {exact}");
        }
    }
}
