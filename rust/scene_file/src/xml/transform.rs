//! `<transform>` and its operations (docs/renderer-semantics.md §3; `src/core/parser.cpp::
//! parse_transform_node`, `include/mitsuba/core/transform.h`, `drjit/transform.h::rotate`,
//! `include/mitsuba/core/vector.h::coordinate_system`).
//!
//! Each operation is LEFT-multiplied onto the matrix built so far (`M = op·M`), so the first
//! listed operation is the first applied to a point.

use glam::{DMat4, DVec3, DVec4};

use super::attrs::Attrs;
use super::numbers::tokenize;
use crate::error::SceneError;

/// Composes `ops` (each the attributes of one child of `<transform>`, in document order).
pub(crate) fn build_transform(ops: Vec<Attrs>) -> Result<DMat4, SceneError> {
    let mut m = DMat4::IDENTITY;
    for op in ops {
        let pos = op.pos.clone();
        m = transform_op(op)? * m;
        if !m.is_finite() {
            return Err(SceneError::at(&pos, "transform contains NaN or infinity"));
        }
    }
    Ok(m)
}

/// The matrix of one operation element.
fn transform_op(mut a: Attrs) -> Result<DMat4, SceneError> {
    let m = match a.tag.as_str() {
        "translate" => {
            a.expand_value_to_xyz()?;
            a.check(&["x", "y", "z"])?;
            DMat4::from_translation(a.xyz(0.0)?)
        }
        "scale" => {
            a.expand_value_to_xyz()?;
            a.check(&["x", "y", "z"])?;
            DMat4::from_scale(a.xyz(1.0)?)
        }
        "rotate" => {
            a.expand_value_to_xyz()?;
            a.check(&["!angle", "x", "y", "z"])?;
            let axis = a.xyz(0.0)?;
            if axis == DVec3::ZERO {
                return Err(a.err("rotation axis cannot be zero"));
            }
            let angle = a.float_value("angle", a.required("angle")?)?;
            rotate(axis, angle)
        }
        "matrix" => {
            a.check(&["!value"])?;
            matrix(&a)?
        }
        "lookat" => {
            a.check(&["!origin", "!target", "up"])?;
            let (origin, target) = (a.vec3_attr("origin")?, a.vec3_attr("target")?);
            let up = match a.get("up") {
                Some(s) if !s.is_empty() => a.vec3_attr("up")?,
                _ => DVec3::ZERO,
            };
            let m = look_at(origin, target, up);
            if !m.is_finite() {
                return Err(a.err(
                    "invalid lookat transformation (origin equals target, or up is parallel to the view direction)",
                ));
            }
            m
        }
        other => return Err(a.err(format!("unexpected <{other}> element inside <transform>"))),
    };
    if !m.is_finite() {
        return Err(a.err(format!("<{}> gives a transform with NaN or infinity", a.tag)));
    }
    Ok(m)
}

/// `value` = 16 (4×4) or 9 (3×3, upper-left) numbers, ROW-major.
fn matrix(a: &Attrs) -> Result<DMat4, SceneError> {
    let s = a.required("value")?;
    let tokens = tokenize(s);
    let n = match tokens.len() {
        16 => 4,
        9 => 3,
        k => return Err(a.err(format!("<matrix> must have 9 or 16 values, got {k}"))),
    };
    let mut rows = DMat4::IDENTITY.to_cols_array_2d(); // symmetric: rows == cols
    for i in 0..n {
        for j in 0..n {
            rows[i][j] = a.float_value("matrix value", tokens[i * n + j])?;
        }
    }
    Ok(DMat4::from_cols_array_2d(&rows).transpose())
}

/// Rotation by `angle_deg` degrees about `axis`, right-handed. The axis is deliberately NOT
/// normalized: Mitsuba (`drjit::rotate`) builds `cosθ·I + (1−cosθ)·a·aᵀ + sinθ·[a]×` from the
/// raw axis, so `x="2"` yields a scaled/sheared matrix (§3 pitfall), reproduced here.
pub fn rotate(axis: DVec3, angle_deg: f64) -> DMat4 {
    let (s, c) = angle_deg.to_radians().sin_cos();
    let (x, y, z) = (axis.x, axis.y, axis.z);
    let k = 1.0 - c;
    DMat4::from_cols(
        DVec4::new(x * x * k + c, y * x * k + z * s, z * x * k - y * s, 0.0),
        DVec4::new(x * y * k - z * s, y * y * k + c, z * y * k + x * s, 0.0),
        DVec4::new(x * z * k + y * s, y * z * k - x * s, z * z * k + c, 0.0),
        DVec4::W,
    )
}

/// Mitsuba's `look_at`: columns (left, up', dir, origin) with dir = normalize(target−origin),
/// left = normalize(up × dir), up' = dir × left. A zero `up` is replaced by the first vector of
/// [`coordinate_system`]`(dir)`, as the parser does. Degenerate input gives NaN (caller checks).
pub fn look_at(origin: DVec3, target: DVec3, up: DVec3) -> DMat4 {
    let dir = (target - origin).normalize();
    let up = if up == DVec3::ZERO { coordinate_system(dir).0 } else { up };
    let left = up.cross(dir).normalize();
    let new_up = dir.cross(left);
    DMat4::from_cols(left.extend(0.0), new_up.extend(0.0), dir.extend(0.0), origin.extend(1.0))
}

/// Two vectors completing unit `n` to an orthonormal basis (Duff et al., JCGT 2017), with
/// Mitsuba's sign convention (`sign(-0.0) = -1`), so a missing lookat `up` matches exactly.
pub fn coordinate_system(n: DVec3) -> (DVec3, DVec3) {
    // drjit's sign(z) and mulsign(v, z) = v·sign(z), both from z's sign bit.
    let sign = 1.0f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (DVec3::new(n.x * n.x * a * sign + 1.0, b * sign, -n.x * sign), DVec3::new(b, n.y * n.y * a + sign, -n.y))
}
