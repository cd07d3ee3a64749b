//! Helpers of Mitsuba's Disney-style BSDFs (`src/bsdfs/principledhelpers.h`, v3.9.1): the
//! GTR1 clearcoat distribution, Schlick terms, the macro/micro-surface side test and the
//! roughness → (α_u, α_v) map. Semantics as there, including the quirks (e.g. `calc_schlick`
//! switches to the refracted cosine when light leaves the denser side), and the property reads
//! both plugins share (`get_flag`: an optional lobe exists when its parameter is given and is
//! not the float 0).

use crate::load::props::PluginProps;
use crate::texture::Texture;
use glam::Vec3;
use matte_brdf::params::{MAX_MAGNITUDE, too_large};
use matte_scene_file::SceneError;
use matte_scene_file::xml::Value;
use std::f32::consts::{PI, TAU};

/// A parameter texture (default: the harvested one); constants beyond [`MAX_MAGNITUDE`] are
/// rejected (Mitsuba takes them, and renders NaN).
pub(crate) fn texture(p: &mut PluginProps, name: &str) -> Result<Texture, SceneError> {
    let t = p.texture(name)?;
    if let Texture::Constant(c) = &t
        && c.max_element() as f64 > MAX_MAGNITUDE
    {
        return Err(p.prop_err(name, too_large(c.max_element() as f64)));
    }
    Ok(t)
}

/// The texture of an optional lobe, `None` when absent or given as the float 0 (Mitsuba's
/// `get_flag`).
pub(crate) fn flagged(p: &mut PluginProps, name: &str) -> Result<Option<Texture>, SceneError> {
    let given_as_zero = matches!(p.raw(name), Some(Value::Float(x)) if *x == 0.0);
    let given = p.has(name);
    let t = texture(p, name)?;
    Ok(if given && !given_as_zero { Some(t) } else { None })
}

/// A `*_sampling_rate` (default 1).
pub(crate) fn sampling_rate(p: &mut PluginProps, name: &str) -> Result<f32, SceneError> {
    let v = p.float(name)?;
    if !(v.is_finite() && (0.0..=MAX_MAGNITUDE).contains(&v)) {
        return Err(p.prop_err(name, format!("must be a finite sampling rate ≥ 0, got {v}")));
    }
    Ok(v as f32)
}

/// (1 − cos)⁵ with cos clamped to [0, 1].
#[inline]
pub fn schlick_weight(cos_i: f32) -> f32 {
    let m = (1.0 - cos_i).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Mitsuba's `calc_schlick(R0, cos_theta_i, eta)`: lerp(w, 1, R0) with w the Schlick weight of
/// |cos θi| when entering the denser side, else of the refracted cosine (0 under TIR).
#[inline]
pub fn calc_schlick(r0: Vec3, cos_i: f32, eta: f32) -> Vec3 {
    let outside = cos_i >= 0.0;
    let (eta_it, eta_ti) = if outside { (eta, 1.0 / eta) } else { (1.0 / eta, eta) };
    let cos_t2 = 1.0 - (1.0 - cos_i * cos_i) * (eta_ti * eta_ti);
    let cos_t = cos_t2.max(0.0).sqrt();
    let w = if eta_it > 1.0 { schlick_weight(cos_i.abs()) } else { schlick_weight(cos_t) };
    Vec3::splat(w) + r0 * (1.0 - w)
}

/// ((η − 1)/(η + 1))².
#[inline]
pub fn schlick_r0_eta(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// `m` flipped to wi's side: Mitsuba's `mulsign(m, cos_theta_i)` (sign bit of the cosine).
#[inline]
fn mulsign(m: Vec3, c: f32) -> Vec3 {
    if c.is_sign_negative() { -m } else { m }
}

/// Mitsuba's `mac_mic_compatibility`: wi on the side of m (oriented like wi's hemisphere), and
/// wo on the same side (reflection) or the other (transmission).
#[inline]
pub fn mac_mic_compatibility(m: Vec3, wi: Vec3, wo: Vec3, cos_i: f32, reflection: bool) -> bool {
    let ms = mulsign(m, cos_i);
    if reflection { wi.dot(ms) > 0.0 && wo.dot(ms) > 0.0 } else { wi.dot(ms) > 0.0 && wo.dot(-ms) > 0.0 }
}

/// Mitsuba's `calc_dist_params`: α = max(0.001, roughness²), stretched by
/// aspect = √(1 − 0.9·anisotropic) when the anisotropic flag is set.
#[inline]
pub fn dist_params(anisotropic: f32, roughness: f32, has_anisotropic: bool) -> (f32, f32) {
    let r2 = roughness * roughness;
    if !has_anisotropic {
        let a = r2.max(0.001);
        return (a, a);
    }
    let aspect = (1.0 - 0.9 * anisotropic).sqrt();
    ((r2 / aspect).max(0.001), (r2 * aspect).max(0.001))
}

/// GGX smith G1 with a fixed α (`smith_ggx1`), used by the clearcoat.
#[inline]
pub fn smith_ggx1(v: Vec3, wh: Vec3, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let c = v.z.abs();
    let c2 = c * c;
    let tan2 = (1.0 - c2) / c2;
    let mut r = 2.0 / (1.0 + (1.0 + a2 * tan2).sqrt());
    if v.z == 1.0 {
        r = 1.0;
    }
    if v.dot(wh) * v.z <= 0.0 {
        r = 0.0;
    }
    r
}

/// The clearcoat's isotropic GTR1 ("Berry") distribution.
#[derive(Clone, Copy, Debug)]
pub struct Gtr1 {
    pub alpha: f32,
}

impl Gtr1 {
    #[inline]
    pub fn eval(&self, m: Vec3) -> f32 {
        let c2 = m.z * m.z;
        let a2 = self.alpha * self.alpha;
        let r = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * c2));
        if r * m.z > 1e-20 { r } else { 0.0 }
    }

    #[inline]
    pub fn pdf(&self, m: Vec3) -> f32 {
        if m.z < 0.0 { 0.0 } else { m.z * self.eval(m) }
    }

    #[inline]
    pub fn sample(&self, u: glam::Vec2) -> Vec3 {
        let (sin_phi, cos_phi) = (TAU * u.x).sin_cos();
        let a2 = self.alpha * self.alpha;
        let cos2 = (1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2);
        let sin_t = (1.0 - cos2).max(0.0).sqrt();
        let cos_t = cos2.max(0.0).sqrt();
        Vec3::new(cos_phi * sin_t, sin_phi * sin_t, cos_t)
    }
}

/// Rec. 709 luminance (Mitsuba's `luminance` in RGB mode).
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.212_671, 0.715_160, 0.072_169))
}

/// Mitsuba's tint colour: the base colour over its luminance (white where that is 0).
#[inline]
pub fn tint_color(base: Vec3) -> Vec3 {
    let lum = luminance(base);
    if lum > 0.0 { base / lum } else { Vec3::ONE }
}

/// The sheen colour: 1 + (tint − 1)·`sheen_tint`, or white without the `sheen_tint` flag.
#[inline]
pub fn sheen_color(base: Vec3, sheen_tint: Option<f32>) -> Vec3 {
    match sheen_tint {
        Some(st) => Vec3::ONE + (tint_color(base) - Vec3::ONE) * st,
        None => Vec3::ONE,
    }
}

/// The diffuse lobe of `principled` and `principledthin` (Burley 2012, with retro-reflection;
/// with the `flatness` flag blended towards the fake subsurface term): the factor of
/// base·|cos θo|/π, from |cos θi|, |cos θo| and cos θd = wh·wo.
#[inline]
pub fn diffuse_lobe(roughness: f32, abs_cos_i: f32, abs_cos_o: f32, cos_d: f32, flatness: Option<f32>) -> f32 {
    let fo = schlick_weight(abs_cos_o);
    let fi = schlick_weight(abs_cos_i);
    let f_diff = (1.0 - 0.5 * fi) * (1.0 - 0.5 * fo);
    let rr = 2.0 * roughness * cos_d * cos_d;
    let f_retro = rr * (fo + fi + fo * fi * (rr - 1.0));
    match flatness {
        Some(flatness) => {
            let fss90 = rr / 2.0;
            let fss = (1.0 + (fss90 - 1.0) * fo) * (1.0 + (fss90 - 1.0) * fi);
            let f_ss = 1.25 * (fss * (1.0 / (abs_cos_o + abs_cos_i) - 0.5) + 0.5);
            let a = f_diff + f_retro;
            a + (f_ss - a) * flatness
        }
        None => f_diff + f_retro,
    }
}
