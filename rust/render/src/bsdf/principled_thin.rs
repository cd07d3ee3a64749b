//! Mitsuba's `principledthin` (`src/bsdfs/principledthin.cpp`, v3.9.1): the thin-surface
//! Disney BSDF (no interior). Both sides behave alike (wi and wo are mirrored to wi's side
//! first). Lobes: diffuse reflection (retro-reflection, `flatness`, sheen), diffuse
//! transmission (`diff_trans`, halved to [0, 1]), a GGX specular reflection with the thin
//! Fresnel mix, and a GGX "transmission" that reflects about the microfacet and mirrors the
//! result through the surface, with the roughness scaled by (0.65·η − 0.35). The specular
//! lobes exist only with `spec_trans` (Mitsuba's `get_flag`); lobe probabilities follow the
//! `*_sampling_rate`s; the sample weight is eval/pdf of the mixture.

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, MicrofacetDistribution};
use super::principled_helpers::{
    calc_schlick, diffuse_lobe, dist_params, flagged, mac_mic_compatibility, sampling_rate, schlick_r0_eta,
    schlick_weight, sheen_color, texture, tint_color,
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
pub struct PrincipledThin {
    pub base_color: Texture,
    pub roughness: Texture,
    pub anisotropic: Option<Texture>,
    pub spec_trans: Option<Texture>,
    pub sheen: Option<Texture>,
    pub sheen_tint: Option<Texture>,
    pub flatness: Option<Texture>,
    pub spec_tint: Option<Texture>,
    pub diff_trans: Option<Texture>,
    /// `eta` (an unbounded texture, default 1.5).
    pub eta: Texture,
    pub spec_refl_srate: f32,
    pub spec_trans_srate: f32,
    pub diff_trans_srate: f32,
    pub diff_refl_srate: f32,
}

#[inline]
fn opt(t: &Option<Texture>, si: &SurfaceInteraction) -> f32 {
    t.as_ref().map_or(0.0, |t| t.eval_1(si))
}

#[inline]
fn mulsign(v: Vec3, c: f32) -> Vec3 {
    if c.is_sign_negative() { -v } else { v }
}

impl FromProps for PrincipledThin {
    /// Every parameter a texture (default: Mitsuba's), the optional lobes by `get_flag`, `eta`
    /// (an unbounded texture, default 1.5) and the sampling rates (default 1).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let eta = p.texture("eta")?;
        if let Texture::Constant(e) = &eta
            && !(e.min_element() > 0.0 && e.max_element() as f64 <= MAX_MAGNITUDE)
        {
            return Err(p.prop_err("eta", format!("must be a positive finite index, got {e}")));
        }
        Ok(PrincipledThin {
            base_color: texture(p, "base_color")?,
            roughness: texture(p, "roughness")?,
            anisotropic: flagged(p, "anisotropic")?,
            spec_trans: flagged(p, "spec_trans")?,
            sheen: flagged(p, "sheen")?,
            sheen_tint: flagged(p, "sheen_tint")?,
            flatness: flagged(p, "flatness")?,
            spec_tint: flagged(p, "spec_tint")?,
            diff_trans: flagged(p, "diff_trans")?,
            eta,
            spec_refl_srate: sampling_rate(p, "specular_reflectance_sampling_rate")?,
            spec_trans_srate: sampling_rate(p, "specular_transmittance_sampling_rate")?,
            diff_trans_srate: sampling_rate(p, "diffuse_transmittance_sampling_rate")?,
            diff_refl_srate: sampling_rate(p, "diffuse_reflectance_sampling_rate")?,
        })
    }
}

impl PrincipledThin {
    /// Normalised (spec reflect, spec trans, diffuse reflect, diffuse trans) probabilities.
    #[inline]
    fn probs(&self, spec_trans: f32, diff_trans: f32) -> [f32; 4] {
        let has_st = self.spec_trans.is_some();
        let sr = if has_st { spec_trans * self.spec_refl_srate / 2.0 } else { 0.0 };
        let st = if has_st { spec_trans * self.spec_trans_srate / 2.0 } else { 0.0 };
        let cr = self.diff_refl_srate * (1.0 - spec_trans) * (1.0 - diff_trans);
        let ct = if self.diff_trans.is_some() { self.diff_trans_srate * (1.0 - spec_trans) * diff_trans } else { 0.0 };
        let rcp = 1.0 / (sr + st + cr + ct);
        [sr * rcp, st * rcp, cr * rcp, ct * rcp]
    }

    /// The two GGX distributions: reflection, and transmission with the scaled roughness.
    #[inline]
    fn distributions(&self, si: &SurfaceInteraction, eta_t: f32) -> (Microfacet, Microfacet) {
        let anisotropic = opt(&self.anisotropic, si);
        let roughness = self.roughness.eval_1(si);
        let has_aniso = self.anisotropic.is_some();
        let (ax, ay) = dist_params(anisotropic, roughness, has_aniso);
        let (sx, sy) = dist_params(anisotropic, (0.65 * eta_t - 0.35) * roughness, has_aniso);
        (Microfacet::new(MicrofacetDistribution::Ggx, ax, ay), Microfacet::new(MicrofacetDistribution::Ggx, sx, sy))
    }

    /// Mitsuba's `eval`: f·|cos θo|.
    pub fn eval(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> Vec3 {
        let cos_i = wi.z;
        if cos_i == 0.0 || !wi.is_finite() || !wo.is_finite() {
            return Vec3::ZERO;
        }
        let roughness = self.roughness.eval_1(si);
        let flatness = opt(&self.flatness, si);
        let spec_trans = opt(&self.spec_trans, si);
        let eta_t = self.eta.eval_1(si);
        let diff_trans = opt(&self.diff_trans, si) / 2.0;
        let base = self.base_color.eval(si);
        let wi = mulsign(wi, cos_i);
        let wo_t = mulsign(wo, cos_i);
        let cos_i = cos_i.abs();
        let cos_o = wo_t.z;
        let (reflect, refract) = (cos_o > 0.0, cos_o < 0.0);
        let wo_r = Vec3::new(wo_t.x, wo_t.y, wo_t.z.abs());
        let wh = (wi + wo_r).normalize();
        let mut value = Vec3::ZERO;
        if self.spec_trans.is_some() {
            let f_diel = fresnel_dielectric(wi.dot(wh), eta_t).r;
            let (refl_distr, trans_distr) = self.distributions(si, eta_t);
            if spec_trans > 0.0 && reflect && mac_mic_compatibility(wh, wi, wo_t, wi.z, true) {
                let spec_tint = opt(&self.spec_tint, si);
                let mut f_schlick = Vec3::ZERO;
                if self.spec_tint.is_some() {
                    f_schlick = calc_schlick(tint_color(base) * schlick_r0_eta(eta_t), wi.dot(wh), eta_t);
                }
                let f_thin = Vec3::splat(f_diel) + (f_schlick - Vec3::splat(f_diel)) * spec_tint;
                let d = refl_distr.d(wh);
                let g = refl_distr.smith_g1(wi, wh) * refl_distr.smith_g1(wo_t, wh);
                value += f_thin * (spec_trans * d * g / (4.0 * cos_i));
            }
            if refract && spec_trans > 0.0 && mac_mic_compatibility(wh, wi, wo_t, wi.z, false) {
                let d = trans_distr.d(wh);
                let g = trans_distr.smith_g1(wi, wh) * trans_distr.smith_g1(wo_t, wh);
                value += base * (spec_trans * (1.0 - f_diel) * d * g / (4.0 * cos_i));
            }
        }
        if reflect && spec_trans < 1.0 && diff_trans < 1.0 {
            let cos_d = wh.dot(wo_t);
            let lobe = diffuse_lobe(roughness, cos_i, cos_o.abs(), cos_d, self.flatness.as_ref().map(|_| flatness));
            value += base * ((1.0 - spec_trans) * cos_o * FRAC_1_PI * (1.0 - diff_trans) * lobe);
            let sheen = opt(&self.sheen, si);
            if self.sheen.is_some() && sheen > 0.0 {
                let fd = schlick_weight(cos_d.abs());
                let tint = sheen_color(base, self.sheen_tint.as_ref().map(|t| t.eval_1(si)));
                value += tint * (sheen * (1.0 - spec_trans) * fd * (1.0 - diff_trans) * cos_o.abs());
            }
        }
        if self.diff_trans.is_some() && refract && spec_trans < 1.0 && diff_trans > 0.0 {
            value += base * ((1.0 - spec_trans) * diff_trans * FRAC_1_PI * cos_o.abs());
        }
        // Extreme parameters (e.g. roughness 1e30 → α = ∞) give NaN in Mitsuba; no
        // contribution here instead.
        if value.is_finite() { value } else { Vec3::ZERO }
    }

    /// Mitsuba's `pdf`.
    pub fn pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> f32 {
        let cos_i = wi.z;
        if cos_i == 0.0 || !wi.is_finite() || !wo.is_finite() {
            return 0.0;
        }
        let spec_trans = opt(&self.spec_trans, si);
        let eta_t = self.eta.eval_1(si);
        let diff_trans = opt(&self.diff_trans, si) / 2.0;
        let wi = mulsign(wi, cos_i);
        let wo_t = mulsign(wo, cos_i);
        let cos_o = wo_t.z;
        let (reflect, refract) = (cos_o > 0.0, cos_o < 0.0);
        let [psr, pst, pcr, pct] = self.probs(spec_trans, diff_trans);
        let mut pdf = 0.0;
        if self.spec_trans.is_some() {
            let wo_r = Vec3::new(wo_t.x, wo_t.y, wo_t.z.abs());
            let wh = (wi + wo_r).normalize();
            let dwh_dwo = (1.0 / (4.0 * wo_r.dot(wh))).abs();
            let (refl_distr, trans_distr) = self.distributions(si, eta_t);
            if mac_mic_compatibility(wh, wi, wo_t, wi.z, true) && reflect {
                pdf += psr * refl_distr.normal_pdf(wi, wh, true) * dwh_dwo;
            }
            if mac_mic_compatibility(wh, wi, wo_t, wi.z, false) && refract {
                pdf += pst * trans_distr.normal_pdf(wi, wh, true) * dwh_dwo;
            }
        }
        if reflect {
            pdf += pcr * FRAC_1_PI * wo_t.z;
        }
        if self.diff_trans.is_some() && refract {
            pdf += pct * FRAC_1_PI * -wo_t.z;
        }
        if pdf.is_finite() { pdf } else { 0.0 }
    }
}

impl Bxdf for PrincipledThin {
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        (self.eval(si, wi, wo), self.pdf(si, wi, wo))
    }

    /// Mitsuba's `sample` (lobe by `u_lobe`, direction by `u`; weight = eval/pdf).
    fn sample(&self, si: &SurfaceInteraction, wi_in: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let cos_i = wi_in.z;
        if cos_i == 0.0 || !wi_in.is_finite() {
            return None;
        }
        let spec_trans = opt(&self.spec_trans, si);
        let diff_trans = opt(&self.diff_trans, si) / 2.0;
        let wi = mulsign(wi_in, cos_i);
        let [psr, pst, pcr, _] = self.probs(spec_trans, diff_trans);
        let has_st = self.spec_trans.is_some();
        let wo = if has_st && u_lobe < psr {
            let (refl_distr, _) = self.distributions(si, self.eta.eval_1(si));
            let m = refl_distr.sample(wi, u, true);
            let wo = 2.0 * wi.dot(m) * m - wi;
            if !(mac_mic_compatibility(m, wi, wo, wi.z, true) && wo.z > 0.0) {
                return None;
            }
            wo
        } else if has_st && u_lobe >= psr && u_lobe < psr + pst {
            let (_, trans_distr) = self.distributions(si, self.eta.eval_1(si));
            let m = trans_distr.sample(wi, u, true);
            let r = 2.0 * wi.dot(m) * m - wi;
            let wo = Vec3::new(r.x, r.y, -r.z);
            if !(mac_mic_compatibility(m, wi, wo, wi.z, false) && wo.z < 0.0) {
                return None;
            }
            wo
        } else if u_lobe >= psr + pst && u_lobe < psr + pst + pcr {
            square_to_cosine_hemisphere(u)
        } else if self.diff_trans.is_some() && u_lobe >= psr + pst + pcr {
            -square_to_cosine_hemisphere(u)
        } else {
            return None;
        };
        let wo = mulsign(wo, cos_i);
        let pdf = self.pdf(si, wi_in, wo);
        if !(pdf > 0.0) || !wo.is_finite() {
            return None;
        }
        let weight = self.eval(si, wi_in, wo) / pdf;
        if !weight.is_finite() {
            return None;
        }
        Some(BsdfSample { wo, weight, pdf, delta: false, eta: 1.0 })
    }

    /// Diffuse reflection and transmission, glossy reflection, glossy transmission with
    /// `spec_trans` (no refraction: the surface is thin), on both sides.
    #[inline]
    fn flags(&self) -> BsdfFlags {
        let flags = BsdfFlags::DIFFUSE_REFLECTION
            | BsdfFlags::DIFFUSE_TRANSMISSION
            | BsdfFlags::GLOSSY_REFLECTION
            | BsdfFlags::FRONT_SIDE
            | BsdfFlags::BACK_SIDE;
        if self.spec_trans.is_some() { flags | BsdfFlags::GLOSSY_TRANSMISSION } else { flags }
    }
}
