//! `<bsdf type="principled">` and `<bsdf type="principledthin">` (Mitsuba's
//! `src/bsdfs/principled.cpp`, `principledthin.cpp`): every parameter may be a texture; an
//! optional lobe exists when its parameter is given and is not the float 0 (`get_flag` in
//! `principledhelpers.h`).

use super::bsdf_params::MAX_MAGNITUDE;
use super::{Builder, err, texture, values};
use crate::render::bsdf::{Principled, principled_thin::PrincipledThin};
use crate::render::texture::Texture;
use crate::scene_file::SceneError;
use crate::scene_file::xml::{ColorUse, SceneObject, Value};
use glam::Vec3;

/// A parameter texture; constants beyond [`MAX_MAGNITUDE`] are rejected (Mitsuba takes them,
/// and renders NaN).
fn tex(b: &Builder, obj: &SceneObject, name: &str, default: f32) -> Result<Texture, SceneError> {
    let t = texture::get(b, obj, name, ColorUse::Bounded, Vec3::splat(default))?;
    if let Texture::Constant(c) = &t
        && c.max_element() as f64 > MAX_MAGNITUDE
    {
        return Err(values::prop_err(obj, name, super::bsdf_params::too_large(c.max_element() as f64)));
    }
    Ok(t)
}

/// The texture of an optional lobe, `None` when absent or given as the float 0.
fn flagged(b: &Builder, obj: &SceneObject, name: &str) -> Result<Option<Texture>, SceneError> {
    let given_as_zero = matches!(obj.properties.get(name).map(|p| &p.value), Some(Value::Float(x)) if *x == 0.0);
    let given = obj.properties.contains(name) || obj.children.iter().any(|c| c.name.as_deref() == Some(name));
    let t = tex(b, obj, name, 0.0)?;
    Ok(if given && !given_as_zero { Some(t) } else { None })
}

/// A `*_sampling_rate` (default 1).
fn rate(obj: &SceneObject, name: &str) -> Result<f32, SceneError> {
    let v = values::float(obj, name, 1.0)?;
    if !(v.is_finite() && (0.0..=MAX_MAGNITUDE).contains(&v)) {
        return Err(values::prop_err(obj, name, format!("must be a finite sampling rate ≥ 0, got {v}")));
    }
    Ok(v as f32)
}

pub fn principled(b: &Builder, obj: &SceneObject) -> Result<Principled, SceneError> {
    let base_color = tex(b, obj, "base_color", 0.5)?;
    let roughness = tex(b, obj, "roughness", 0.5)?;
    let anisotropic = flagged(b, obj, "anisotropic")?;
    let spec_trans = flagged(b, obj, "spec_trans")?;
    let sheen = flagged(b, obj, "sheen")?;
    let sheen_tint = flagged(b, obj, "sheen_tint")?;
    let flatness = flagged(b, obj, "flatness")?;
    let spec_tint = flagged(b, obj, "spec_tint")?;
    let metallic = flagged(b, obj, "metallic")?;
    let clearcoat = flagged(b, obj, "clearcoat")?;
    let clearcoat_gloss = tex(b, obj, "clearcoat_gloss", 0.0)?;
    let spec_srate = rate(obj, "main_specular_sampling_rate")?;
    let clearcoat_srate = rate(obj, "clearcoat_sampling_rate")?;
    let diff_refl_srate = rate(obj, "diffuse_reflectance_sampling_rate")?;
    if obj.properties.contains("eta") && obj.properties.contains("specular") {
        return Err(err(obj, "give either eta or specular, not both (as in Mitsuba)"));
    }
    let eta = values::float_opt(obj, "eta")?;
    if let Some(e) = eta
        && !(e.is_finite() && e > 0.0 && e <= MAX_MAGNITUDE)
    {
        return Err(values::prop_err(obj, "eta", format!("must be a positive finite index, got {e}")));
    }
    let specular = values::float_opt(obj, "specular")?;
    if let Some(s) = specular
        && !(s.is_finite() && (0.0..12.5).contains(&s))
    {
        return Err(values::prop_err(
            obj,
            "specular",
            format!("must be in [0, 12.5) (η = 2/(1 − √(0.08·specular)) − 1), got {s}"),
        ));
    }
    let eta = Principled::eta_from(eta.map(|e| e as f32), specular.map(|s| s as f32), spec_trans.is_some());
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

pub fn principled_thin(b: &Builder, obj: &SceneObject) -> Result<PrincipledThin, SceneError> {
    let eta = texture::get(b, obj, "eta", ColorUse::Unbounded, Vec3::splat(1.5))?;
    if let Texture::Constant(e) = &eta
        && !(e.min_element() > 0.0 && e.max_element() as f64 <= MAX_MAGNITUDE)
    {
        return Err(values::prop_err(obj, "eta", format!("must be a positive finite index, got {e}")));
    }
    Ok(PrincipledThin {
        base_color: tex(b, obj, "base_color", 0.5)?,
        roughness: tex(b, obj, "roughness", 0.5)?,
        anisotropic: flagged(b, obj, "anisotropic")?,
        spec_trans: flagged(b, obj, "spec_trans")?,
        sheen: flagged(b, obj, "sheen")?,
        sheen_tint: flagged(b, obj, "sheen_tint")?,
        flatness: flagged(b, obj, "flatness")?,
        spec_tint: flagged(b, obj, "spec_tint")?,
        diff_trans: flagged(b, obj, "diff_trans")?,
        eta,
        spec_refl_srate: rate(obj, "specular_reflectance_sampling_rate")?,
        spec_trans_srate: rate(obj, "specular_transmittance_sampling_rate")?,
        diff_trans_srate: rate(obj, "diffuse_transmittance_sampling_rate")?,
        diff_refl_srate: rate(obj, "diffuse_reflectance_sampling_rate")?,
    })
}
