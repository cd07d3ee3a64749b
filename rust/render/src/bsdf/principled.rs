//! Mitsuba's `principled` (`src/bsdfs/principled.cpp`, v3.9.1): the Disney BSDF with a
//! diffuse base (retro-reflection, optional fake subsurface `flatness`), sheen, a GGX specular
//! reflection lobe with the "principled" Fresnel mix (dielectric, metallic Schlick on the base
//! colour, tinted Schlick), a GGX transmission lobe (`spec_trans`), and a GTR1 clearcoat.
//!
//! Each optional lobe exists only when its parameter is given (and is not the float 0), as
//! Mitsuba's `get_flag`; the lobe is chosen by probabilities proportional to its weight and
//! the `*_sampling_rate`s, and the sample weight is eval/pdf of the whole mixture. Formulas,
//! gates and quirks follow the Mitsuba source (e.g. the clearcoat term has no 1/(4 cos θi),
//! and in scalar variants sheen is only added where the diffuse lobe is active).

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, MicrofacetDistribution};
use super::principled_helpers::{
    Gtr1, calc_schlick, diffuse_lobe, dist_params, flagged, luminance, mac_mic_compatibility, sampling_rate,
    schlick_r0_eta, schlick_weight, sheen_color, smith_ggx1, texture,
};
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_brdf::params::MAX_MAGNITUDE;
use matte_brdf::sampling::square_to_cosine_hemisphere;
use matte_scene_file::SceneError;
use std::f32::consts::FRAC_1_PI;

/// Parameters as Mitsuba reads them; `None` = the lobe's flag is off.
#[derive(Clone, Debug)]
pub struct Principled {
    pub base_color: Texture,
    pub roughness: Texture,
    pub anisotropic: Option<Texture>,
    pub spec_trans: Option<Texture>,
    pub sheen: Option<Texture>,
    pub sheen_tint: Option<Texture>,
    pub flatness: Option<Texture>,
    pub spec_tint: Option<Texture>,
    pub metallic: Option<Texture>,
    pub clearcoat: Option<Texture>,
    pub clearcoat_gloss: Texture,
    pub spec_srate: f32,
    pub clearcoat_srate: f32,
    pub diff_refl_srate: f32,
    /// Relative index (from `eta`, or from `specular` by η = 2/(1 − √(0.08·specular)) − 1).
    pub eta: f32,
}

/// The per-hit parameter values.
struct Local {
    base: Vec3,
    roughness: f32,
    metallic: f32,
    clearcoat: f32,
    brdf: f32,
    bsdf: f32,
    distr: Microfacet,
}

#[inline]
fn opt(t: &Option<Texture>, si: &SurfaceInteraction) -> f32 {
    t.as_ref().map_or(0.0, |t| t.eval_1(si))
}

impl FromProps for Principled {
    /// Every parameter a texture (default: Mitsuba's), the optional lobes by `get_flag`, the
    /// sampling rates (default 1), and `eta` or `specular` (not both).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let base_color = texture(p, "base_color")?;
        let roughness = texture(p, "roughness")?;
        let anisotropic = flagged(p, "anisotropic")?;
        let spec_trans = flagged(p, "spec_trans")?;
        let sheen = flagged(p, "sheen")?;
        let sheen_tint = flagged(p, "sheen_tint")?;
        let flatness = flagged(p, "flatness")?;
        let spec_tint = flagged(p, "spec_tint")?;
        let metallic = flagged(p, "metallic")?;
        let clearcoat = flagged(p, "clearcoat")?;
        let clearcoat_gloss = texture(p, "clearcoat_gloss")?;
        let spec_srate = sampling_rate(p, "main_specular_sampling_rate")?;
        let clearcoat_srate = sampling_rate(p, "clearcoat_sampling_rate")?;
        let diff_refl_srate = sampling_rate(p, "diffuse_reflectance_sampling_rate")?;
        if p.has_property("eta") && p.has_property("specular") {
            return Err(p.err("give either eta or specular, not both (as in Mitsuba)"));
        }
        let eta = p.float_opt("eta")?;
        if let Some(e) = eta
            && !(e.is_finite() && e > 0.0 && e <= MAX_MAGNITUDE)
        {
            return Err(p.prop_err("eta", format!("must be a positive finite index, got {e}")));
        }
        let specular = p.float("specular")?;
        if !(specular.is_finite() && (0.0..12.5).contains(&specular)) {
            return Err(p.prop_err(
                "specular",
                format!("must be in [0, 12.5) (η = 2/(1 − √(0.08·specular)) − 1), got {specular}"),
            ));
        }
        let eta = Principled::eta_from(eta.map(|e| e as f32), Some(specular as f32), spec_trans.is_some());
        Ok(Principled {
            base_color,
            roughness,
            anisotropic,
            spec_trans,
            sheen,
            sheen_tint,
            flatness,
            spec_tint,
            metallic,
            clearcoat,
            clearcoat_gloss,
            spec_srate,
            clearcoat_srate,
            diff_refl_srate,
            eta,
        })
    }
}

impl Principled {
    /// η from Mitsuba's `eta`/`specular` properties: `eta` wins if given (1 → 1.001 with a
    /// transmission lobe); else `specular` (default 0.5; 0 → 1e-3 with transmission).
    pub fn eta_from(eta: Option<f32>, specular: Option<f32>, has_spec_trans: bool) -> f32 {
        match eta {
            Some(e) => {
                if has_spec_trans && e == 1.0 {
                    1.001
                } else {
                    e
                }
            }
            None => {
                let mut s = specular.unwrap_or(0.5);
                if has_spec_trans && s == 0.0 {
                    s = 1e-3;
                }
                2.0 / (1.0 - (0.08 * s).sqrt()) - 1.0
            }
        }
    }

    #[inline]
    fn local(&self, si: &SurfaceInteraction) -> Local {
        let anisotropic = opt(&self.anisotropic, si);
        let roughness = self.roughness.eval_1(si);
        let spec_trans = opt(&self.spec_trans, si);
        let metallic = opt(&self.metallic, si);
        let clearcoat = opt(&self.clearcoat, si);
        let (ax, ay) = dist_params(anisotropic, roughness, self.anisotropic.is_some());
        Local {
            base: self.base_color.eval(si),
            roughness,
            metallic,
            clearcoat,
            brdf: (1.0 - metallic) * (1.0 - spec_trans),
            bsdf: if self.spec_trans.is_some() { (1.0 - metallic) * spec_trans } else { 0.0 },
            distr: Microfacet::new(MicrofacetDistribution::Ggx, ax, ay),
        }
    }

    /// Lobe probabilities (diffuse, clearcoat, transmission, reflection), normalised; `f` is
    /// the dielectric Fresnel at the (sampled or reconstructed) microfacet normal.
    #[inline]
    fn lobe_probs(&self, p: &Local, front: bool, f: f32) -> [f32; 4] {
        let spec_reflect = if front { self.spec_srate * (1.0 - p.bsdf * (1.0 - f)) } else { f };
        let spec_trans = if self.spec_trans.is_some() {
            if front { self.spec_srate * p.bsdf * (1.0 - f) } else { 1.0 - f }
        } else {
            0.0
        };
        let clearcoat = if self.clearcoat.is_some() && front { 0.25 * p.clearcoat * self.clearcoat_srate } else { 0.0 };
        let diffuse = if front { p.brdf * self.diff_refl_srate } else { 0.0 };
        let rcp = 1.0 / (spec_reflect + spec_trans + clearcoat + diffuse);
        [diffuse * rcp, clearcoat * rcp, spec_trans * rcp, spec_reflect * rcp]
    }

    /// Generalised half vector (upper hemisphere) and η along the path.
    #[inline]
    fn half(&self, wi: Vec3, wo: Vec3) -> (Vec3, f32, bool, bool) {
        let reflect = wi.z * wo.z > 0.0;
        let refract = wi.z * wo.z < 0.0;
        let eta_path = if wi.z > 0.0 { self.eta } else { 1.0 / self.eta };
        let wh = (wi + wo * if reflect { 1.0 } else { eta_path }).normalize();
        (if wh.z.is_sign_negative() { -wh } else { wh }, eta_path, reflect, refract)
    }

    /// Mitsuba's `eval`: f·|cos θo|.
    pub fn eval(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> Vec3 {
        let cos_i = wi.z;
        if cos_i == 0.0 || !wi.is_finite() || !wo.is_finite() {
            return Vec3::ZERO;
        }
        let p = self.local(si);
        let flatness = opt(&self.flatness, si);
        let sheen = opt(&self.sheen, si);
        let cos_o = wo.z;
        let front = cos_i > 0.0;
        let (wh, eta_path, reflect, refract) = self.half(wi, wo);
        let inv_eta_path = 1.0 / eta_path;
        let fr = fresnel_dielectric(wi.dot(wh), self.eta);
        let f_diel = fr.r;
        let refl_ok = mac_mic_compatibility(wh, wi, wo, cos_i, true);
        let trans_ok = mac_mic_compatibility(wh, wi, wo, cos_i, false);
        let d = p.distr.d(wh);
        let g = p.distr.smith_g1(wi, wh) * p.distr.smith_g1(wo, wh);
        let mut value = Vec3::ZERO;

        if reflect && refl_ok && f_diel > 0.0 {
            let lum = if self.spec_tint.is_some() { luminance(p.base) } else { 1.0 };
            let spec_tint = opt(&self.spec_tint, si);
            let f = self.principled_fresnel(f_diel, p.metallic, spec_tint, p.base, lum, wi.dot(wh), front, p.bsdf);
            value += f * (d * g / (4.0 * cos_i.abs()));
        }
        if self.spec_trans.is_some() && p.bsdf > 0.0 && refract && trans_ok && f_diel < 1.0 {
            let (ih, oh) = (wi.dot(wh), wo.dot(wh));
            let denom = ih + eta_path * oh;
            let t = (inv_eta_path * inv_eta_path * (1.0 - f_diel) * d * g * eta_path * eta_path * ih * oh)
                / (cos_i * denom * denom);
            value += p.base.map(f32::sqrt) * (p.bsdf * t.abs());
        }
        if self.clearcoat.is_some() && p.clearcoat > 0.0 && reflect && refl_ok && front {
            let gloss = self.clearcoat_gloss.eval_1(si);
            let fcc = calc_schlick(Vec3::splat(0.04), wi.dot(wh), self.eta).x;
            let dcc = Gtr1 { alpha: 0.1 + (0.001 - 0.1) * gloss }.eval(wh);
            let gcc = smith_ggx1(wi, wh, 0.25) * smith_ggx1(wo, wh, 0.25);
            value += Vec3::splat(p.clearcoat * 0.25 * fcc * dcc * gcc * cos_o.abs());
        }
        if p.brdf > 0.0 && reflect && front {
            let cos_d = wh.dot(wo);
            let flat = self.flatness.as_ref().map(|_| flatness);
            let lobe = diffuse_lobe(p.roughness, cos_i.abs(), cos_o.abs(), cos_d, flat);
            value += p.base * (p.brdf * cos_o.abs() * FRAC_1_PI * lobe);
            if self.sheen.is_some() && sheen > 0.0 && 1.0 - p.metallic > 0.0 {
                let fd = schlick_weight(cos_d.abs());
                let tint = sheen_color(p.base, self.sheen_tint.as_ref().map(|t| t.eval_1(si)));
                value += tint * (sheen * (1.0 - p.metallic) * fd * cos_o.abs());
            }
        }
        // Extreme parameters (e.g. roughness 1e30 → α = ∞) give NaN in Mitsuba; no
        // contribution here instead.
        if value.is_finite() { value } else { Vec3::ZERO }
    }

    /// Mitsuba's `principled_fresnel`.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn principled_fresnel(
        &self,
        f_diel: f32,
        metallic: f32,
        spec_tint: f32,
        base: Vec3,
        lum: f32,
        cos_i: f32,
        front: bool,
        bsdf: f32,
    ) -> Vec3 {
        if !front {
            return Vec3::splat(bsdf * f_diel);
        }
        let eta_it = if cos_i >= 0.0 { self.eta } else { 1.0 / self.eta };
        let mut f_schlick = Vec3::ZERO;
        if self.metallic.is_some() {
            f_schlick += metallic * calc_schlick(base, cos_i, self.eta);
        }
        if self.spec_tint.is_some() {
            let c_tint = if lum > 0.0 { base / lum } else { Vec3::ONE };
            let f0 = c_tint * schlick_r0_eta(eta_it);
            f_schlick += (1.0 - metallic) * spec_tint * calc_schlick(f0, cos_i, self.eta);
        }
        Vec3::splat((1.0 - metallic) * (1.0 - spec_tint) * f_diel) + f_schlick
    }

    /// Mitsuba's `pdf`.
    pub fn pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> f32 {
        let cos_i = wi.z;
        if cos_i == 0.0 || !wi.is_finite() || !wo.is_finite() {
            return 0.0;
        }
        let p = self.local(si);
        let front = cos_i > 0.0;
        let (wh, eta_path, reflect, refract) = self.half(wi, wo);
        let f = fresnel_dielectric(wi.dot(wh), self.eta).r;
        let [pd, pc, pt, pr] = self.lobe_probs(&p, front, f);
        let (ih, oh) = (wi.dot(wh), wo.dot(wh));
        let dwh_dwo = if self.spec_trans.is_some() && !reflect {
            let denom = ih + eta_path * oh;
            (eta_path * eta_path * oh / (denom * denom)).abs()
        } else {
            (1.0 / (4.0 * oh)).abs()
        };
        let wi_up = if cos_i.is_sign_negative() { -wi } else { wi };
        let spec_pdf = || p.distr.normal_pdf(wi_up, wh, true) * dwh_dwo;
        let refl_ok = mac_mic_compatibility(wh, wi, wo, cos_i, true) && reflect;
        let mut pdf = 0.0;
        if refl_ok {
            pdf += pr * spec_pdf();
        }
        if reflect {
            pdf += pd * FRAC_1_PI * wo.z;
        }
        if self.spec_trans.is_some() && refract && mac_mic_compatibility(wh, wi, wo, cos_i, false) {
            pdf += pt * spec_pdf();
        }
        if self.clearcoat.is_some() && refl_ok {
            let gloss = self.clearcoat_gloss.eval_1(si);
            pdf += pc * Gtr1 { alpha: 0.1 + (0.001 - 0.1) * gloss }.pdf(wh) * dwh_dwo;
        }
        if pdf.is_finite() { pdf } else { 0.0 }
    }
}

impl Bxdf for Principled {
    /// `(f·|cos θo|, pdf)`.
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        (self.eval(si, wi, wo), self.pdf(si, wi, wo))
    }

    /// Mitsuba's `sample`: picks a lobe by `u_lobe`, draws its direction from `u`, weight =
    /// eval/pdf of the mixture. `None` where Mitsuba returns zero.
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let cos_i = wi.z;
        if cos_i == 0.0 || !wi.is_finite() {
            return None;
        }
        let p = self.local(si);
        let front = cos_i > 0.0;
        if !(front || p.bsdf > 0.0) {
            return None;
        }
        let wi_up = if cos_i.is_sign_negative() { -wi } else { wi };
        let m_spec = p.distr.sample(wi_up, u, true);
        let fr = fresnel_dielectric(wi.dot(m_spec), self.eta);
        let [pd, pc, pt, _] = self.lobe_probs(&p, front, fr.r);
        let mut eta = 1.0;
        let wo = if u_lobe < pd {
            let wo = square_to_cosine_hemisphere(u);
            if !(cos_i * wo.z > 0.0) {
                return None;
            }
            wo
        } else if self.clearcoat.is_some() && u_lobe < pd + pc {
            let gloss = self.clearcoat_gloss.eval_1(si);
            let m = Gtr1 { alpha: 0.1 + (0.001 - 0.1) * gloss }.sample(u);
            let wo = 2.0 * wi.dot(m) * m - wi;
            if !(mac_mic_compatibility(m, wi, wo, cos_i, true) && cos_i * wo.z > 0.0) {
                return None;
            }
            wo
        } else if self.spec_trans.is_some() && u_lobe >= pd + pc && u_lobe < pd + pc + pt {
            let wo = m_spec * wi.dot(m_spec).mul_add(fr.eta_ti, fr.cos_t) - wi * fr.eta_ti;
            if !(mac_mic_compatibility(m_spec, wi, wo, cos_i, false) && cos_i * wo.z < 0.0) {
                return None;
            }
            eta = fr.eta_it;
            wo
        } else {
            let wo = 2.0 * wi.dot(m_spec) * m_spec - wi;
            if !(mac_mic_compatibility(m_spec, wi, wo, cos_i, true) && cos_i * wo.z > 0.0) {
                return None;
            }
            wo
        };
        let pdf = self.pdf(si, wi, wo);
        if !(pdf > 0.0) || !wo.is_finite() {
            return None;
        }
        let weight = self.eval(si, wi, wo) / pdf;
        if !weight.is_finite() {
            return None;
        }
        Some(BsdfSample { wo, weight, pdf, delta: false, eta })
    }

    /// Diffuse and glossy reflection (the specular lobe on both sides); glossy transmission
    /// (refraction) with `spec_trans`.
    #[inline]
    fn flags(&self) -> BsdfFlags {
        let reflection =
            BsdfFlags::DIFFUSE_REFLECTION | BsdfFlags::GLOSSY_REFLECTION | BsdfFlags::FRONT_SIDE | BsdfFlags::BACK_SIDE;
        if self.spec_trans.is_some() {
            reflection | BsdfFlags::GLOSSY_TRANSMISSION | BsdfFlags::NON_SYMMETRIC
        } else {
            reflection
        }
    }
}
