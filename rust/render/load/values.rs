//! Typed property access with Mitsuba's defaults and range checks, shared by the plugin
//! builders: every error names the property's own line.

use glam::{Affine3A, DMat4, Mat3, Vec3};
use matte_scene_file::SceneError;
use matte_scene_file::xml::{ColorUse, SceneObject};

pub fn float(obj: &SceneObject, name: &str, default: f64) -> Result<f64, SceneError> {
    Ok(obj.properties.float(name)?.unwrap_or(default))
}

pub fn float_opt(obj: &SceneObject, name: &str) -> Result<Option<f64>, SceneError> {
    obj.properties.float(name)
}

pub fn boolean(obj: &SceneObject, name: &str, default: bool) -> Result<bool, SceneError> {
    Ok(obj.properties.boolean(name)?.unwrap_or(default))
}

pub fn string(obj: &SceneObject, name: &str, default: &str) -> Result<String, SceneError> {
    Ok(obj.properties.string(name)?.unwrap_or_else(|| default.to_string()))
}

/// An integer that must lie in `[lo, hi]`.
pub fn integer(obj: &SceneObject, name: &str, default: i64, lo: i64, hi: i64) -> Result<i64, SceneError> {
    let v = obj.properties.integer(name)?.unwrap_or(default);
    if v < lo || v > hi {
        return Err(prop_err(obj, name, format!("must be in [{lo}, {hi}], got {v}")));
    }
    Ok(v)
}

/// A float that must be finite (NaN or ∞ would give NaN pixels).
pub fn finite(obj: &SceneObject, name: &str, default: f64) -> Result<f64, SceneError> {
    let v = float(obj, name, default)?;
    if !v.is_finite() {
        return Err(prop_err(obj, name, format!("must be a finite number, got {v}")));
    }
    Ok(v)
}

/// A float that must be finite and strictly positive.
pub fn positive(obj: &SceneObject, name: &str, default: f64) -> Result<f64, SceneError> {
    let v = float(obj, name, default)?;
    if !(v.is_finite() && v > 0.0) {
        return Err(prop_err(obj, name, format!("must be a positive number, got {v}")));
    }
    Ok(v)
}

/// A constant colour read as `usage` demands (docs/renderer-semantics.md §2). NaN or ∞ is an error for every
/// usage, and so is a negative reflectance-like value (`<float>`/`<spectrum>`; the parser
/// already rejects an `<rgb>` outside [0, 1]). Mitsuba takes such floats silently; they
/// would only produce NaN or negative pixels. A `<float>` reflectance above 1 stays
/// allowed, as in Mitsuba.
pub fn color(obj: &SceneObject, name: &str, usage: ColorUse, default: Vec3) -> Result<Vec3, SceneError> {
    let Some(c) = obj.properties.color(name, usage)? else { return Ok(default) };
    let v = Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32);
    if !v.is_finite() {
        return Err(prop_err(obj, name, format!("must be finite, got {v}")));
    }
    if usage == ColorUse::Bounded && v.min_element() < 0.0 {
        return Err(prop_err(obj, name, format!("must not be negative, got {v}")));
    }
    Ok(v)
}

/// `to_world` (or another transform) as an f32 affine map; identity when absent. Projective
/// rows are rejected (Mitsuba's shapes use affine transforms).
pub fn transform(obj: &SceneObject, name: &str) -> Result<Affine3A, SceneError> {
    match obj.properties.transform(name)? {
        None => Ok(Affine3A::IDENTITY),
        Some(m) => to_affine(&m).ok_or_else(|| prop_err(obj, name, "must be affine (last row 0 0 0 1) and finite")),
    }
}

pub fn to_affine(m: &DMat4) -> Option<Affine3A> {
    let r = m.row(3);
    if r != glam::DVec4::new(0.0, 0.0, 0.0, 1.0) || !m.is_finite() {
        return None;
    }
    let m3 =
        Mat3::from_cols(m.x_axis.truncate().as_vec3(), m.y_axis.truncate().as_vec3(), m.z_axis.truncate().as_vec3());
    Some(Affine3A::from_mat3_translation(m3, m.w_axis.truncate().as_vec3()))
}

/// An error about property `name` of `obj`, at the property's line when it exists.
pub fn prop_err(obj: &SceneObject, name: &str, what: impl Into<String>) -> SceneError {
    let pos = obj.properties.iter().find(|p| p.name == name).map(|p| p.pos.clone()).unwrap_or_else(|| obj.pos.clone());
    SceneError::at(&pos, format!("{} \"{}\": property \"{name}\" {}", obj.tag, obj.plugin, what.into()))
}

/// The first non-empty line of a message from a file-format library (ply-rs-bw, for one,
/// appends its parser state over several lines): scene errors are one line.
pub fn one_line(msg: &str) -> &str {
    msg.lines().map(str::trim).find(|l| !l.is_empty()).unwrap_or("")
}
