//! Property readers shared by the `<bsdf>` builders: indices of refraction (numbers or
//! Mitsuba's names), constant `specular_*` weights, and the microfacet parameters Mitsuba's
//! `MicrofacetDistribution(const Properties &)` reads (`include/mitsuba/render/microfacet.h`).

use super::{Builder, err, texture, values};
use crate::render::bsdf::MicrofacetDistribution;
use crate::render::texture::Texture;
use crate::scene_file::SceneError;
use crate::scene_file::xml::{ColorUse, SceneObject, Value};
use glam::Vec3;

pub use crate::brdf::params::{MAX_MAGNITUDE, too_large};

/// A float or a named IOR (Mitsuba's table, shared with the kernels).
pub fn ior(obj: &SceneObject, name: &str, default: f64) -> Result<f32, SceneError> {
    let v = match obj.properties.get(name).map(|p| p.value.clone()) {
        None => default,
        Some(Value::String(s)) => crate::brdf::params::lookup_ior(&s)
            .ok_or_else(|| values::prop_err(obj, name, format!("unknown IOR name \"{s}\"")))?,
        Some(_) => values::float(obj, name, default)?,
    };
    if !(v.is_finite() && v >= 1.0) {
        return Err(values::prop_err(obj, name, format!("must be ≥ 1, got {v}")));
    }
    if v > MAX_MAGNITUDE {
        return Err(values::prop_err(obj, name, too_large(v)));
    }
    Ok(v as f32)
}

/// int_ior / ext_ior (ext default air), in f32 as Mitsuba; the two must differ (Mitsuba's
/// `roughdielectric`/`roughplastic`: "must be positive and differ").
pub fn relative_ior(obj: &SceneObject, int_default: f64) -> Result<f32, SceneError> {
    let (int_ior, ext_ior) = (ior(obj, "int_ior", int_default)?, ior(obj, "ext_ior", 1.000277)?);
    if int_ior == ext_ior {
        return Err(values::prop_err(obj, "int_ior", format!("must differ from ext_ior (both are {int_ior})")));
    }
    Ok(int_ior / ext_ior)
}

/// `specular_*` weights: constant colours only (default 1).
pub fn constant(obj: &SceneObject, name: &str) -> Result<Vec3, SceneError> {
    Ok(optional_constant(obj, name)?.unwrap_or(Vec3::ONE))
}

/// A constant colour that Mitsuba only multiplies with when it is given (`None` if absent).
pub fn optional_constant(obj: &SceneObject, name: &str) -> Result<Option<Vec3>, SceneError> {
    if obj.child(name).is_some() {
        return Err(err(obj, format!("a texture for \"{name}\" is not supported by matte render")));
    }
    if !obj.properties.contains(name) {
        return Ok(None);
    }
    values::color(obj, name, ColorUse::Bounded, Vec3::ONE).map(Some)
}

/// The microfacet parameters of a rough BSDF.
pub struct MicrofacetParams {
    pub kind: MicrofacetDistribution,
    pub alpha_u: f32,
    pub alpha_v: f32,
    pub sample_visible: bool,
    /// Roughness textures (α_u, α_v) when a texture is nested for `alpha`/`alpha_u`/`alpha_v`.
    pub alpha_tex: Option<(Texture, Texture)>,
}

/// `distribution` (beckmann | ggx, case-insensitive; default beckmann), `alpha` (default
/// 0.1) or both `alpha_u`/`alpha_v`, `sample_visible` (default true). With
/// `anisotropic = false` (roughplastic) α_u ≠ α_v is an error, as in Mitsuba. α = 0 is valid
/// (raised to 1e-4 later); a negative roughness, which Mitsuba would take silently, is an
/// error here. Roughness textures (nested `<texture name="alpha…">`) are read when `textures`
/// is given (roughconductor, roughdielectric: Mitsuba's `get_unbounded_texture`), else an error
/// (roughplastic reads plain floats).
pub fn microfacet(
    textures: Option<&Builder>,
    obj: &SceneObject,
    anisotropic: bool,
) -> Result<MicrofacetParams, SceneError> {
    let kind = match values::string(obj, "distribution", "beckmann")?.to_lowercase().as_str() {
        "beckmann" => MicrofacetDistribution::Beckmann,
        "ggx" => MicrofacetDistribution::Ggx,
        other => {
            return Err(values::prop_err(obj, "distribution", format!("must be beckmann or ggx, got \"{other}\"")));
        }
    };
    let nested = |n: &str| obj.children.iter().any(|c| c.name.as_deref() == Some(n));
    if textures.is_none() {
        for name in ["alpha", "alpha_u", "alpha_v"] {
            if nested(name) {
                return Err(err(
                    obj,
                    format!("a texture for \"{name}\" is not supported by {} (give a number, as Mitsuba)", obj.plugin),
                ));
            }
        }
    }
    let has = |n: &str| obj.properties.contains(n) || nested(n);
    let names = match (has("alpha"), has("alpha_u"), has("alpha_v")) {
        (_, false, false) => ["alpha", "alpha"],
        // With all three, `alpha` stays unread and is reported at its own line.
        (_, true, true) => ["alpha_u", "alpha_v"],
        _ => return Err(err(obj, "alpha_u and alpha_v must be given together")),
    };
    let sample_visible = values::boolean(obj, "sample_visible", true)?;
    if let Some(b) = textures
        && (nested(names[0]) || nested(names[1]))
    {
        let tu = texture::get(b, obj, names[0], ColorUse::Unbounded, Vec3::splat(0.1))?;
        let tv = texture::get(b, obj, names[1], ColorUse::Unbounded, Vec3::splat(0.1))?;
        return Ok(MicrofacetParams { kind, alpha_u: 0.1, alpha_v: 0.1, sample_visible, alpha_tex: Some((tu, tv)) });
    }
    let (au, av) = (values::float(obj, names[0], 0.1)?, values::float(obj, names[1], 0.1)?);
    for (n, a) in [(names[0], au), (names[1], av)] {
        if !(a.is_finite() && a >= 0.0) {
            return Err(values::prop_err(obj, n, format!("roughness must be finite and ≥ 0, got {a}")));
        }
        if a > MAX_MAGNITUDE {
            return Err(values::prop_err(obj, n, too_large(a)));
        }
    }
    if !anisotropic && au != av {
        return Err(values::prop_err(
            obj,
            "alpha_u",
            format!("{} does not support anisotropic roughness (as in Mitsuba)", obj.plugin),
        ));
    }
    Ok(MicrofacetParams { kind, alpha_u: au as f32, alpha_v: av as f32, sample_visible, alpha_tex: None })
}
