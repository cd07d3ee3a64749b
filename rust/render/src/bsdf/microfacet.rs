//! Beckmann and GGX microfacet distributions as Mitsuba 3.9.1 defines them
//! (`include/mitsuba/render/microfacet.h`, docs/renderer-semantics.md §10): the normal distribution D,
//! Smith's masking G1 (Beckmann by its rational approximation, as Mitsuba), and the density
//! of the microfacet normal either sampler draws. The samplers themselves are in
//! [`super::vndf`] (visible normals) and [`Microfacet::sample_d_cos`] (plain D·cos θ).

use super::vndf;
use crate::load::props::PluginProps;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_brdf::params::{MAX_MAGNITUDE, too_large};
use matte_scene_file::SceneError;
use std::f32::consts::{PI, TAU};

/// Which normal distribution function.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MicrofacetDistribution {
    /// Gaussian slopes (Mitsuba's default for `roughconductor`).
    Beckmann,
    /// Trowbridge–Reitz.
    Ggx,
}

/// A distribution with its (possibly anisotropic) roughness: `alpha_u` along the shading
/// tangent (x), `alpha_v` along the bitangent (y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    pub kind: MicrofacetDistribution,
    pub alpha_u: f32,
    pub alpha_v: f32,
}

/// Mitsuba clamps roughness to at least 1e-4 (`MicrofacetDistribution::configure`), so that α
/// = 0 gives a very sharp lobe instead of a division by zero.
pub const MIN_ALPHA: f32 = 1e-4;

/// The microfacet parameters of a rough BSDF as read from its properties.
pub struct MicrofacetParams {
    pub kind: MicrofacetDistribution,
    pub alpha_u: f32,
    pub alpha_v: f32,
    pub sample_visible: bool,
    /// Roughness textures (α_u, α_v) when a texture is nested for `alpha`/`alpha_u`/`alpha_v`.
    pub alpha_tex: Option<(Texture, Texture)>,
}

/// α when no roughness is given: `roughconductor`'s and `roughdielectric`'s default, and the
/// default argument of `MicrofacetDistribution(props)` that `roughplastic` uses.
const DEFAULT_ALPHA: f64 = 0.1;

impl MicrofacetParams {
    /// `distribution` (beckmann | ggx, case-insensitive; default beckmann), `alpha` (default
    /// 0.1) or both `alpha_u`/`alpha_v`, `sample_visible` (default true), as
    /// `roughconductor.cpp`, `roughdielectric.cpp` and `MicrofacetDistribution(const Properties
    /// &)` (`include/mitsuba/render/microfacet.h`) read them. With `anisotropic = false`
    /// (roughplastic) α_u ≠ α_v is an error, as in Mitsuba. α = 0 is valid (raised to 1e-4
    /// later); a negative roughness, which Mitsuba would take silently, is an error here.
    /// Roughness textures (nested `<texture name="alpha…">`) are read when `textures` is set
    /// (roughconductor, roughdielectric: Mitsuba's `get_unbounded_texture`), else an error
    /// (roughplastic reads plain floats).
    pub(crate) fn from_props(p: &mut PluginProps, textures: bool, anisotropic: bool) -> Result<Self, SceneError> {
        let plugin = &p.object().plugin;
        let kind = match p.string_opt("distribution")?.unwrap_or_else(|| "beckmann".into()).to_lowercase().as_str() {
            "beckmann" => MicrofacetDistribution::Beckmann,
            "ggx" => MicrofacetDistribution::Ggx,
            other => {
                return Err(p.prop_err("distribution", format!("must be beckmann or ggx, got \"{other}\"")));
            }
        };
        if !textures {
            for name in ["alpha", "alpha_u", "alpha_v"] {
                if p.is_nested(name) {
                    return Err(p.err(format!(
                        "a texture for \"{name}\" is not supported by {plugin} (give a number, as Mitsuba)"
                    )));
                }
            }
        }
        let names = match (p.has("alpha_u"), p.has("alpha_v")) {
            (false, false) => ["alpha", "alpha"],
            // With all three, `alpha` stays unread and is reported at its own line.
            (true, true) => ["alpha_u", "alpha_v"],
            _ => return Err(p.err("alpha_u and alpha_v must be given together")),
        };
        let sample_visible = p.boolean_opt("sample_visible")?.unwrap_or(true);
        if textures && (p.is_nested(names[0]) || p.is_nested(names[1])) {
            let (tu, tv) = (p.texture(names[0])?, p.texture(names[1])?);
            return Ok(MicrofacetParams {
                kind,
                alpha_u: 0.1,
                alpha_v: 0.1,
                sample_visible,
                alpha_tex: Some((tu, tv)),
            });
        }
        let au = p.float_opt(names[0])?.unwrap_or(DEFAULT_ALPHA);
        let av = p.float_opt(names[1])?.unwrap_or(DEFAULT_ALPHA);
        for (n, a) in [(names[0], au), (names[1], av)] {
            if !(a.is_finite() && a >= 0.0) {
                return Err(p.prop_err(n, format!("roughness must be finite and ≥ 0, got {a}")));
            }
            if a > MAX_MAGNITUDE {
                return Err(p.prop_err(n, too_large(a)));
            }
        }
        if !anisotropic && au != av {
            return Err(
                p.prop_err("alpha_u", format!("{plugin} does not support anisotropic roughness (as in Mitsuba)"))
            );
        }
        Ok(MicrofacetParams { kind, alpha_u: au as f32, alpha_v: av as f32, sample_visible, alpha_tex: None })
    }
}

impl Microfacet {
    /// Roughness below [`MIN_ALPHA`] is raised to it; the caller rejects negative/NaN input.
    pub fn new(kind: MicrofacetDistribution, alpha_u: f32, alpha_v: f32) -> Self {
        Microfacet { kind, alpha_u: alpha_u.max(MIN_ALPHA), alpha_v: alpha_v.max(MIN_ALPHA) }
    }

    /// D(m) in 1/sr (projected: ∫ D(m) cos θm dm = 1). Zero where D·cos θm ≤ 1e-20, as Mitsuba
    /// ("prevent potential numerical issues"), which also zeroes the lower hemisphere.
    #[inline]
    pub fn d(&self, m: Vec3) -> f32 {
        let (au, av) = (self.alpha_u, self.alpha_v);
        let c2 = m.z * m.z;
        let sx = m.x / au;
        let sy = m.y / av;
        let v = match self.kind {
            // exp(−tan²θ·(cos²φ/αu² + sin²φ/αv²)) / (π αu αv cos⁴θ)
            MicrofacetDistribution::Beckmann => (-(sx * sx + sy * sy) / c2).exp() / (PI * au * av * c2 * c2),
            MicrofacetDistribution::Ggx => {
                let q = sx * sx + sy * sy + c2;
                1.0 / (PI * au * av * q * q)
            }
        };
        // `v * m.z > 1e-20` is false for NaN (m.z = 0 in Beckmann gives exp(−∞)/0 = 0/0).
        if v * m.z > 1e-20 { v } else { 0.0 }
    }

    /// Smith's G1(v, m): 1 at normal incidence, 0 if `v` sees the back of the microfacet
    /// (`dot(v, m)·v.z ≤ 0`). Beckmann uses Mitsuba's rational fit (< 0.35 % error) rather
    /// than the erf form, so that eval/pdf match Mitsuba's numbers.
    #[inline]
    pub fn smith_g1(&self, v: Vec3, m: Vec3) -> f32 {
        let xy = (self.alpha_u * v.x).powi(2) + (self.alpha_v * v.y).powi(2);
        let tan2 = xy / (v.z * v.z);
        let g = match self.kind {
            MicrofacetDistribution::Beckmann => {
                // a = 1/(α tan θ); f32 division by +∞ gives 0, so grazing `v` gives G1 = 0.
                let a = tan2.sqrt().recip();
                if a >= 1.6 { 1.0 } else { (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a) }
            }
            MicrofacetDistribution::Ggx => 2.0 / (1.0 + (1.0 + tan2).sqrt()),
        };
        let g = if xy == 0.0 { 1.0 } else { g };
        if v.dot(m) * v.z <= 0.0 { 0.0 } else { g }
    }

    /// Solid-angle density of the microfacet normal `m` drawn by [`Self::sample`] for incident
    /// `wi` (`wi.z > 0`): the visible-normal density D(m)·G1(wi, m)·|wi·m| / cos θi, or
    /// D(m)·cos θm for plain sampling.
    #[inline]
    pub fn normal_pdf(&self, wi: Vec3, m: Vec3, sample_visible: bool) -> f32 {
        let d = self.d(m);
        if sample_visible { d * self.smith_g1(wi, m) * wi.dot(m).abs() / wi.z } else { d * m.z }
    }

    /// Draws a microfacet normal for incident `wi` (`wi.z > 0`) from the visible normals or
    /// from D·cos θm. Degenerate draws return a normal whose [`Self::normal_pdf`] is 0.
    #[inline]
    pub fn sample(&self, wi: Vec3, u: Vec2, sample_visible: bool) -> Vec3 {
        if sample_visible {
            match self.kind {
                MicrofacetDistribution::Ggx => vndf::sample_ggx(wi, self.alpha_u, self.alpha_v, u),
                MicrofacetDistribution::Beckmann => vndf::sample_beckmann(wi, self.alpha_u, self.alpha_v, u),
            }
        } else {
            self.sample_d_cos(u)
        }
    }

    /// Normal with density D(m)·cos θm (Walter et al. 2007, anisotropic as in microfacet.h):
    /// `u.y` picks the azimuth, whose marginal is uniform after mapping tan φ' → (αv/αu) tan φ'
    /// (in the same quadrant); `u.x` then inverts the 1-D slope CDF with the effective α along
    /// that azimuth.
    #[inline]
    pub fn sample_d_cos(&self, u: Vec2) -> Vec3 {
        let (au, av) = (self.alpha_u, self.alpha_v);
        let (s, c) = (TAU * u.y).sin_cos();
        // Direction of (αu cos φ', αv sin φ'): tan φ = (αv/αu)·tan φ', quadrant kept.
        let (cx, sy) = (au * c, av * s);
        let inv_len = (cx * cx + sy * sy).sqrt().recip();
        let (cos_phi, sin_phi) = (cx * inv_len, sy * inv_len);
        let alpha2 = ((cos_phi / au).powi(2) + (sin_phi / av).powi(2)).recip();
        let tan2 = match self.kind {
            // P(tan²θ > t) = exp(−t/α²)
            MicrofacetDistribution::Beckmann => -alpha2 * (1.0 - u.x).ln(),
            // P(tan²θ ≤ t) = t / (t + α²)
            MicrofacetDistribution::Ggx => alpha2 * u.x / (1.0 - u.x),
        };
        // u.x → 1 gives tan² = ∞ → cos θ = 0: a horizontal normal with D·cos θ = 0.
        let cos_t = (1.0 + tan2).sqrt().recip();
        let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
        Vec3::new(cos_phi * sin_t, sin_phi * sin_t, cos_t)
    }
}
