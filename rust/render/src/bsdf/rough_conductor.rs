//! Mitsuba's `roughconductor` (`src/bsdfs/roughconductor.cpp`, docs/renderer-semantics.md §10): a
//! one-sided Cook–Torrance microfacet reflector with the complex-index Fresnel term,
//!
//! ```text
//! f·cos θo = F(wi·h) · D(h) · G1(wi, h) · G1(wo, h) / (4 cos θi),   h = normalize(wi + wo)
//! ```
//!
//! sampled through the microfacet normal (visible normals by default, or D·cos θm).
//!
//! The roughness is a number or a texture (`alpha`, or `alpha_u`/`alpha_v`; Mitsuba reads them
//! with `get_unbounded_texture` and builds the distribution from their `eval_1` at every
//! hit). Numbers give one distribution, computed once; with a texture the lobe is copied per
//! hit with the textures' roughness (raised to 1e-4 as in Mitsuba).

use super::bxdf::Bxdf;
use super::conductor_ior::conductor_ior_from_props;
use super::flags::BsdfFlags;
use super::fresnel::fresnel_conductor;
use super::microfacet::{Microfacet, MicrofacetDistribution, MicrofacetParams};
use super::parameter_checks::{check_colour, check_finite};
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Rough conductor (radiance transport).
#[derive(Clone, Debug)]
pub struct RoughConductor {
    /// The lobe at the constant roughness (with textured roughness: at α = 0.1, unused).
    lobe: Lobe,
    /// (α_u, α_v) as textures, evaluated per hit; `None`: the roughness is constant.
    alpha_tex: Option<Box<[Texture; 2]>>,
}

/// Equal parameters; a textured roughness is never equal (textures have no equality).
impl PartialEq for RoughConductor {
    fn eq(&self, other: &Self) -> bool {
        self.alpha_tex.is_none() && other.alpha_tex.is_none() && self.lobe == other.lobe
    }
}

impl FromProps for RoughConductor {
    /// The microfacet parameters (roughness textures allowed), `material` or `eta`/`k`, and a
    /// constant `specular_reflectance` (default 1).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let mf = MicrofacetParams::from_props(p, true, true)?;
        let (eta, k) = conductor_ior_from_props(p)?;
        let r = p.constant_color("specular_reflectance")?;
        let b =
            RoughConductor::new(mf.kind, mf.alpha_u, mf.alpha_v, mf.sample_visible, eta, k, r).map_err(|e| p.err(e))?;
        Ok(match mf.alpha_tex {
            None => b,
            Some((u, v)) => RoughConductor { alpha_tex: Some(Box::new([u, v])), ..b },
        })
    }
}

impl RoughConductor {
    /// α is used directly (not squared) and raised to at least 1e-4, as Mitsuba does; for an
    /// isotropic surface pass the same value twice. Mitsuba's defaults: Beckmann, α = 0.1,
    /// `sample_visible` true, material "none" (η = 0, k = 1). Negative or non-finite
    /// roughness, non-finite `eta`/`k` and negative colours are errors.
    pub fn new(
        distribution: MicrofacetDistribution,
        alpha_u: f32,
        alpha_v: f32,
        sample_visible: bool,
        eta: Vec3,
        k: Vec3,
        specular_reflectance: Vec3,
    ) -> Result<Self, String> {
        for (name, a) in [("alpha_u", alpha_u), ("alpha_v", alpha_v)] {
            if !(a.is_finite() && a >= 0.0) {
                return Err(format!("roughconductor: {name} must be a finite non-negative roughness, got {a}"));
            }
        }
        check_finite("roughconductor", "eta", eta)?;
        check_finite("roughconductor", "k", k)?;
        check_colour("roughconductor", "specular_reflectance", specular_reflectance)?;
        let distr = Microfacet::new(distribution, alpha_u, alpha_v);
        Ok(RoughConductor { lobe: Lobe { distr, sample_visible, eta, k, specular_reflectance }, alpha_tex: None })
    }

    /// The microfacet distribution at the constant roughness (after Mitsuba's 1e-4 clamp).
    pub fn distribution(&self) -> Microfacet {
        self.lobe.distr
    }

    /// Mitsuba's `eval` at the constant roughness: f·cos θo per channel; zero unless both
    /// directions are strictly above the surface. (A textured roughness needs the hit:
    /// [`Bxdf::eval_pdf`].)
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3) -> Vec3 {
        self.lobe.eval(wi, wo)
    }

    /// Mitsuba's `pdf` at the constant roughness (solid angle, of [`Self::sample`]); zero
    /// below the surface and where the micro- and macro-surface disagree on the side.
    #[inline]
    pub fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.lobe.pdf(wi, wo)
    }

    /// Mitsuba's `sample` at the constant roughness: draws a microfacet normal m (`u`;
    /// `u_lobe` is unused) and reflects `wi` about it. Weight F(wi·m)·G1(wo, m) (visible
    /// normals) or F·G1(wi, m)·G1(wo, m)·(wi·m)/(cos θi cos θm) (plain), times
    /// `specular_reflectance`. `None` for `wi` below or on the surface and for draws that
    /// Mitsuba would return with zero weight or zero pdf (wo below the surface, m facing away
    /// from wi).
    #[inline]
    pub fn sample(&self, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        self.lobe.sample(wi, u_lobe, u)
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

impl Bxdf for RoughConductor {
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
        BsdfFlags::GLOSSY_REFLECTION | BsdfFlags::FRONT_SIDE
    }
}

/// The lobe at one roughness.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Lobe {
    distr: Microfacet,
    sample_visible: bool,
    eta: Vec3,
    k: Vec3,
    specular_reflectance: Vec3,
}

impl Lobe {
    /// The same lobe with roughness (α_u, α_v) from a texture: raised to 1e-4 as Mitsuba's
    /// `MicrofacetDistribution` does (NaN becomes 1e-4, negative values too).
    #[inline]
    fn with_alpha(&self, alpha_u: f32, alpha_v: f32) -> Self {
        Self { distr: Microfacet::new(self.distr.kind, alpha_u, alpha_v), ..*self }
    }

    /// See [`RoughConductor::eval`].
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> Vec3 {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return Vec3::ZERO;
        }
        // wi + wo ≠ 0 as both are above the surface.
        let h = (wi + wo).normalize();
        let d = self.distr.d(h);
        let g = self.distr.smith_g1(wi, h) * self.distr.smith_g1(wo, h);
        let f = fresnel_conductor(wi.dot(h), self.eta, self.k);
        // G1(wi, h) ∝ cos θi at grazing, so the quotient stays bounded.
        (f * self.specular_reflectance) * (d * g / (4.0 * wi.z))
    }

    /// See [`RoughConductor::pdf`].
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return 0.0;
        }
        let h = (wi + wo).normalize();
        let (cos_ih, cos_oh) = (wi.dot(h), wo.dot(h));
        if !(cos_ih > 0.0 && cos_oh > 0.0) {
            return 0.0;
        }
        let p = if self.sample_visible {
            self.distr.d(h) * self.distr.smith_g1(wi, h) / (4.0 * wi.z)
        } else {
            // D(h)·cos θh times the Jacobian 1/(4 wo·h) of the half-vector map.
            self.distr.d(h) * h.z / (4.0 * cos_oh)
        };
        // Plain sampling's density is unbounded at grazing mirror pairs (cos_oh → 0 with h
        // near the normal); keep it finite for the MIS weights.
        p.min(f32::MAX)
    }

    /// See [`RoughConductor::sample`].
    #[inline]
    fn sample(&self, wi: Vec3, _u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wi.z.is_nan() || wi.z <= 0.0 {
            return None;
        }
        let m = self.distr.sample(wi, u, self.sample_visible);
        let cos_im = wi.dot(m);
        let wo = 2.0 * cos_im * m - wi;
        let pdf_m = self.distr.normal_pdf(wi, m, self.sample_visible);
        // NaN-safe: every comparison with NaN is false.
        if !(wo.z > 0.0 && cos_im > 0.0 && pdf_m > 0.0) {
            return None;
        }
        let g = if self.sample_visible {
            self.distr.smith_g1(wo, m)
        } else {
            self.distr.smith_g1(wi, m) * self.distr.smith_g1(wo, m) * cos_im / (wi.z * m.z)
        };
        let f = fresnel_conductor(cos_im, self.eta, self.k);
        // wo·m = wi·m for a reflection about m.
        let pdf = (pdf_m / (4.0 * cos_im)).min(f32::MAX);
        Some(BsdfSample { wo, weight: f * self.specular_reflectance * g, pdf, delta: false, eta: 1.0 })
    }
}
