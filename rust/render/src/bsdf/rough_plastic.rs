//! Mitsuba's `roughplastic` (`src/bsdfs/roughplastic.cpp`, v3.9.1): a diffuse base under a
//! rough dielectric coating (isotropic Beckmann or GGX). Two lobes:
//!
//! ```text
//! specular: F(wi·h)·D(h)·G1(wi,h)·G1(wo,h) / (4 cos θi) · specular_reflectance
//! diffuse:  ρ' · cos θo/π · T(θi)·T(θo) / η²,   ρ' = ρ/(1 − R_int)  (nonlinear: ρ/(1 − ρ R_int))
//! ```
//!
//! T is the external transmittance of the rough interface, tabulated at 64 cosines and
//! interpolated linearly; R_int the internal diffuse reflectance (both in
//! [`super::microfacet_albedo`], computed at construction as Mitsuba does in
//! `parameters_changed`). The lobe is picked with p_s ∝ (1 − T(θi))·w and p_d ∝ T(θi)·(1 − w),
//! w = mean(specular)/(mean(diffuse) + mean(specular)); the pdf is the mixture of the
//! microfacet reflection density and the cosine density, and the sample weight is eval/pdf
//! (Mitsuba evaluates both lobes for either choice). One-sided.

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, MicrofacetDistribution, MicrofacetParams};
use super::microfacet_albedo::{TABLE_RES, external_transmittance, internal_reflectance, lerp_table};
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_brdf::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use matte_scene_file::SceneError;
use std::f32::consts::FRAC_1_PI;

/// Rough plastic.
#[derive(Clone, Debug)]
pub struct RoughPlastic {
    distr: Microfacet,
    sample_visible: bool,
    eta: f32,
    inv_eta_2: f32,
    diffuse: Texture,
    specular: Option<Vec3>,
    specular_sampling_weight: f32,
    nonlinear: bool,
    external_transmittance: Box<[f32; TABLE_RES]>,
    internal_reflectance: f32,
}

impl FromProps for RoughPlastic {
    /// The microfacet parameters (isotropic, numbers only, as Mitsuba's
    /// `MicrofacetDistribution(props)`), `int_ior`/`ext_ior` (polypropylene over air; they must
    /// differ), `diffuse_reflectance` (a texture, default 0.5), a constant
    /// `specular_reflectance` if given, `nonlinear` (default false).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let mf = MicrofacetParams::from_props(p, false, false)?;
        let eta = p.relative_ior()?;
        let diffuse = p.texture("diffuse_reflectance")?;
        let specular = p.optional_constant_color("specular_reflectance")?;
        let nonlinear = p.boolean("nonlinear")?;
        RoughPlastic::new(mf.kind, mf.alpha_u, mf.sample_visible, eta, diffuse, specular, nonlinear)
            .map_err(|e| p.err(e))
    }
}

impl RoughPlastic {
    /// `alpha` ≥ 0 (raised to 1e-4), `eta` = int_ior/ext_ior ≠ 1. Mitsuba's defaults: Beckmann,
    /// α = 0.1, visible-normal sampling, polypropylene (1.49) over air.
    pub fn new(
        kind: MicrofacetDistribution,
        alpha: f32,
        sample_visible: bool,
        eta: f32,
        diffuse: Texture,
        specular: Option<Vec3>,
        nonlinear: bool,
    ) -> Result<Self, String> {
        if !(eta.is_finite() && eta > 0.0 && eta != 1.0) {
            return Err(format!("roughplastic: int_ior/ext_ior must be positive, finite and differ from 1, got {eta}"));
        }
        if !(alpha.is_finite() && alpha >= 0.0) {
            return Err(format!("roughplastic: alpha must be a finite non-negative roughness, got {alpha}"));
        }
        if let Some(s) = specular {
            super::parameter_checks::check_colour("roughplastic", "specular_reflectance", s)?;
        }
        let distr = Microfacet::new(kind, alpha, alpha);
        let s_mean = specular.map_or(1.0, |s| (s.x + s.y + s.z) / 3.0);
        let w = s_mean / (diffuse.mean() + s_mean);
        Ok(RoughPlastic {
            distr,
            sample_visible,
            eta,
            inv_eta_2: 1.0 / (eta * eta),
            diffuse,
            specular,
            specular_sampling_weight: w,
            nonlinear,
            external_transmittance: Box::new(external_transmittance(kind, distr.alpha_u, eta)),
            internal_reflectance: internal_reflectance(kind, distr.alpha_u, eta),
        })
    }

    /// The precomputed internal reflectance R_int (for tests).
    pub fn internal_reflectance(&self) -> f32 {
        self.internal_reflectance
    }

    /// The external transmittance T(cos θ), interpolated as Mitsuba does (for tests).
    pub fn transmittance(&self, cos_theta: f32) -> f32 {
        lerp_table(&self.external_transmittance, cos_theta)
    }

    /// Normalised probability of the specular lobe given T(θi).
    #[inline]
    fn prob_specular(&self, t_i: f32) -> f32 {
        let w = self.specular_sampling_weight;
        let ps = (1.0 - t_i) * w;
        let pd = t_i * (1.0 - w);
        ps / (ps + pd)
    }
}

impl Bxdf for RoughPlastic {
    /// `(f·cos θo, pdf)`; zero unless both directions are above the surface.
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return (Vec3::ZERO, 0.0);
        }
        let t_i = lerp_table(&self.external_transmittance, wi.z);
        let prob_specular = self.prob_specular(t_i);
        let prob_diffuse = 1.0 - prob_specular;
        let h = (wo + wi).normalize();
        let d = self.distr.d(h);
        let g1_wi = self.distr.smith_g1(wi, h);
        let pdf_spec = if self.sample_visible {
            d * g1_wi / (4.0 * wi.z)
        } else {
            self.distr.normal_pdf(wi, h, false) / (4.0 * wo.dot(h))
        };
        let pdf = pdf_spec * prob_specular + prob_diffuse * cosine_hemisphere_pdf(wo);

        let f = fresnel_dielectric(wi.dot(h), self.eta).r;
        let g = self.distr.smith_g1(wo, h) * g1_wi;
        let spec = self.specular.unwrap_or(Vec3::ONE) * (f * d * g / (4.0 * wi.z));
        let t_o = lerp_table(&self.external_transmittance, wo.z);
        let rho = self.diffuse.eval(si);
        let rho = if self.nonlinear {
            rho / (Vec3::ONE - rho * self.internal_reflectance)
        } else {
            rho / (1.0 - self.internal_reflectance)
        };
        let value = spec + rho * (FRAC_1_PI * self.inv_eta_2 * wo.z * t_i * t_o);
        (value, pdf)
    }

    /// Lobe by `u_lobe`, direction by `u` (microfacet reflection or cosine-weighted); weight =
    /// eval/pdf of the full mixture. `None` where Mitsuba's weight is zero (pdf 0).
    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if !(wi.z > 0.0) {
            return None;
        }
        let t_i = lerp_table(&self.external_transmittance, wi.z);
        let wo = if u_lobe < self.prob_specular(t_i) {
            let m = self.distr.sample(wi, u, self.sample_visible);
            2.0 * wi.dot(m) * m - wi
        } else {
            square_to_cosine_hemisphere(u)
        };
        let (f, pdf) = self.eval_pdf(si, wi, wo);
        if !(pdf > 0.0) || !pdf.is_finite() || !wo.is_finite() {
            return None;
        }
        Some(BsdfSample { wo, weight: f / pdf, pdf, delta: false, eta: 1.0 })
    }

    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::GLOSSY_REFLECTION | BsdfFlags::DIFFUSE_REFLECTION | BsdfFlags::FRONT_SIDE
    }
}
