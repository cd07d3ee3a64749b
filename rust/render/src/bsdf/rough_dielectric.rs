//! Mitsuba's `roughdielectric` (`src/bsdfs/roughdielectric.cpp`, v3.9.1; Walter et al. 2007):
//! a rough glass interface, two-sided, with a glossy reflection and a glossy transmission
//! lobe. With η the relative index on wi's side (η = int/ext from outside, its inverse from
//! inside) and the generalised half vector m = ±normalize(wi + η·wo) (m = normalize(wi + wo)
//! for reflection), flipped to the upper hemisphere:
//!
//! ```text
//! reflection:   F·D·G / (4 |cos θi|)
//! transmission: |(1/η)² (1 − F)·D·G·η²·(wi·m)(wo·m) / (cos θi (wi·m + η wo·m)²)|
//! ```
//!
//! (radiance transport: the (1/η)² solid-angle compression is included). Sampling draws m
//! from the visible normals of wi mirrored to the upper side (or from D·cos θm with Walter's
//! roughness scale 1.2 − 0.2·√|cos θi| when `sample_visible` is false), then reflects with
//! probability F(wi·m), else refracts.
//!
//! The roughness is a number or a texture, as in `roughconductor`
//! ([`super::rough_conductor`]): numbers give one distribution, computed once; with a texture
//! the lobe is copied per hit with the textures' roughness.

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, MicrofacetDistribution, MicrofacetParams};
use super::parameter_checks::check_colour;
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Rough dielectric (radiance transport).
#[derive(Clone, Debug)]
pub struct RoughDielectric {
    /// The lobe at the constant roughness (with textured roughness: at α = 0.1, unused).
    lobe: Lobe,
    /// (α_u, α_v) as textures, evaluated per hit; `None`: the roughness is constant.
    alpha_tex: Option<Box<[Texture; 2]>>,
}

impl FromProps for RoughDielectric {
    /// The microfacet parameters (roughness textures allowed), `int_ior`/`ext_ior` (bk7 over
    /// air; they must differ) and constant `specular_*` weights (default 1).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let mf = MicrofacetParams::from_props(p, true, true)?;
        let eta = p.relative_ior()?;
        let r = p.constant_color("specular_reflectance")?;
        let t = p.constant_color("specular_transmittance")?;
        let b = RoughDielectric::new(mf.kind, mf.alpha_u, mf.alpha_v, mf.sample_visible, eta, r, t)
            .map_err(|e| p.err(e))?;
        Ok(RoughDielectric { alpha_tex: mf.alpha_tex.map(|(u, v)| Box::new([u, v])), ..b })
    }
}

impl RoughDielectric {
    /// α ≥ 0 (raised to 1e-4), `eta` = int_ior/ext_ior ≠ 1. Mitsuba's defaults: Beckmann,
    /// α = 0.1, visible normals, bk7 over air.
    pub fn new(
        kind: MicrofacetDistribution,
        alpha_u: f32,
        alpha_v: f32,
        sample_visible: bool,
        eta: f32,
        specular_reflectance: Vec3,
        specular_transmittance: Vec3,
    ) -> Result<Self, String> {
        let lobe =
            Lobe::new(kind, alpha_u, alpha_v, sample_visible, eta, specular_reflectance, specular_transmittance)?;
        Ok(RoughDielectric { lobe, alpha_tex: None })
    }

    /// Relative index of refraction η = int_ior / ext_ior.
    pub fn eta(&self) -> f32 {
        self.lobe.eta
    }

    /// `f` applied to the lobe at the hit's roughness.
    #[inline]
    fn at<R>(&self, si: &SurfaceInteraction, f: impl FnOnce(&Lobe) -> R) -> R {
        match &self.alpha_tex {
            None => f(&self.lobe),
            Some(t) => f(&self.lobe.with_alpha(t[0].eval_1(si), t[1].eval_1(si))),
        }
    }
}

impl Bxdf for RoughDielectric {
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        self.at(si, |l| (l.eval(wi, wo), l.pdf(wi, wo)))
    }

    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        self.at(si, |l| l.sample(wi, u_lobe, u))
    }

    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::GLOSSY_REFLECTION
            | BsdfFlags::GLOSSY_TRANSMISSION
            | BsdfFlags::NON_SYMMETRIC
            | BsdfFlags::FRONT_SIDE
            | BsdfFlags::BACK_SIDE
    }
}

/// The lobe at one roughness.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Lobe {
    distr: Microfacet,
    sample_visible: bool,
    eta: f32,
    inv_eta: f32,
    specular_reflectance: Vec3,
    specular_transmittance: Vec3,
}

impl Lobe {
    /// See [`RoughDielectric::new`].
    fn new(
        kind: MicrofacetDistribution,
        alpha_u: f32,
        alpha_v: f32,
        sample_visible: bool,
        eta: f32,
        specular_reflectance: Vec3,
        specular_transmittance: Vec3,
    ) -> Result<Self, String> {
        if !(eta.is_finite() && eta > 0.0 && eta != 1.0) {
            return Err(format!(
                "roughdielectric: int_ior/ext_ior must be positive, finite and differ from 1, got {eta}"
            ));
        }
        for (name, a) in [("alpha_u", alpha_u), ("alpha_v", alpha_v)] {
            if !(a.is_finite() && a >= 0.0) {
                return Err(format!("roughdielectric: {name} must be a finite non-negative roughness, got {a}"));
            }
        }
        check_colour("roughdielectric", "specular_reflectance", specular_reflectance)?;
        check_colour("roughdielectric", "specular_transmittance", specular_transmittance)?;
        Ok(Lobe {
            distr: Microfacet::new(kind, alpha_u, alpha_v),
            sample_visible,
            eta,
            inv_eta: 1.0 / eta,
            specular_reflectance,
            specular_transmittance,
        })
    }

    /// The same lobe with roughness (α_u, α_v) from a texture: raised to 1e-4 as Mitsuba's
    /// `MicrofacetDistribution` does (NaN becomes 1e-4, negative values too).
    #[inline]
    fn with_alpha(&self, alpha_u: f32, alpha_v: f32) -> Self {
        Self { distr: Microfacet::new(self.distr.kind, alpha_u, alpha_v), ..*self }
    }

    /// The distribution used for sampling and the pdf: Walter's widened lobe without visible
    /// normals.
    #[inline]
    fn sample_distr(&self, cos_i: f32) -> Microfacet {
        if self.sample_visible {
            self.distr
        } else {
            let s = 1.2 - 0.2 * cos_i.abs().sqrt();
            Microfacet { alpha_u: self.distr.alpha_u * s, alpha_v: self.distr.alpha_v * s, ..self.distr }
        }
    }

    /// Generalised half vector (upper hemisphere), η on wi's side, and whether it reflects.
    #[inline]
    fn half_vector(&self, wi: Vec3, wo: Vec3) -> (Vec3, f32, bool) {
        let reflect = wi.z * wo.z > 0.0;
        let eta = if wi.z > 0.0 { self.eta } else { self.inv_eta };
        let m = (wi + wo * if reflect { 1.0 } else { eta }).normalize();
        (m * m.z.signum(), eta, reflect)
    }

    /// Mitsuba's `eval` (radiance): f·|cos θo|.
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> Vec3 {
        if wi.z == 0.0 || !wi.is_finite() || !wo.is_finite() {
            return Vec3::ZERO;
        }
        let (m, eta, reflect) = self.half_vector(wi, wo);
        let inv_eta = 1.0 / eta;
        let d = self.distr.d(m);
        let f = fresnel_dielectric(wi.dot(m), self.eta).r;
        let g = self.distr.smith_g1(wi, m) * self.distr.smith_g1(wo, m);
        let v = if reflect {
            self.specular_reflectance * (f * d * g / (4.0 * wi.z.abs()))
        } else {
            let (im, om) = (wi.dot(m), wo.dot(m));
            let denom = im + eta * om;
            let t = (inv_eta * inv_eta * (1.0 - f) * d * g * eta * eta * im * om) / (wi.z * denom * denom);
            self.specular_transmittance * t.abs()
        };
        if v.is_finite() { v } else { Vec3::ZERO }
    }

    /// Mitsuba's `pdf` of [`Self::sample`] (solid angle).
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        if wi.z == 0.0 || !wi.is_finite() || !wo.is_finite() {
            return 0.0;
        }
        let (m, eta, reflect) = self.half_vector(wi, wo);
        let (im, om) = (wi.dot(m), wo.dot(m));
        if !(im * wi.z > 0.0 && om * wo.z > 0.0) {
            return 0.0;
        }
        let dwh_dwo = if reflect {
            1.0 / (4.0 * om)
        } else {
            let denom = im + eta * om;
            eta * eta * om / (denom * denom)
        };
        let wi_up = wi * wi.z.signum();
        let mut prob = self.sample_distr(wi.z).normal_pdf(wi_up, m, self.sample_visible);
        let f = fresnel_dielectric(im, self.eta).r;
        prob *= if reflect { f } else { 1.0 - f };
        let p = prob * dwh_dwo.abs();
        if p.is_finite() { p } else { 0.0 }
    }

    /// Mitsuba's `sample` (radiance). `None` where Mitsuba returns a zero weight or pdf.
    #[inline]
    fn sample(&self, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wi.z == 0.0 || !wi.is_finite() {
            return None;
        }
        let sd = self.sample_distr(wi.z);
        let wi_up = wi * wi.z.signum();
        let m = sd.sample(wi_up, u, self.sample_visible);
        let pdf_m = sd.normal_pdf(wi_up, m, self.sample_visible);
        if !(pdf_m > 0.0) {
            return None;
        }
        let fr = fresnel_dielectric(wi.dot(m), self.eta);
        let (wo, mut weight, pdf_lobe, eta_out, dwh_dwo) = if u_lobe <= fr.r {
            let wo = 2.0 * wi.dot(m) * m - wi;
            (wo, self.specular_reflectance, fr.r, 1.0, 1.0 / (4.0 * wo.dot(m)))
        } else {
            let wo = m * wi.dot(m).mul_add(fr.eta_ti, fr.cos_t) - wi * fr.eta_ti;
            let eta = fr.eta_it;
            let denom = wi.dot(m) + eta * wo.dot(m);
            (
                wo,
                self.specular_transmittance * (fr.eta_ti * fr.eta_ti),
                1.0 - fr.r,
                eta,
                eta * eta * wo.dot(m) / (denom * denom),
            )
        };
        weight *= if self.sample_visible {
            self.distr.smith_g1(wo, m)
        } else {
            self.distr.smith_g1(wi, m) * self.distr.smith_g1(wo, m) * wi.dot(m) / (wi.z * m.z)
        };
        let pdf = pdf_m * pdf_lobe * dwh_dwo.abs();
        if !(pdf > 0.0 && pdf.is_finite() && weight.is_finite() && wo.is_finite()) || weight == Vec3::ZERO {
            return None;
        }
        Some(BsdfSample { wo, weight, pdf, delta: false, eta: eta_out })
    }
}
