//! What Mitsuba's sensors read alike (`src/render/sensor.cpp`): the clip range and focus
//! distance of its `ProjectiveCamera` base ([`clip_range`], every sensor), the field of view
//! (`parse_fov`: [`field_of_view`], [`x_half_tan`]; `perspective`, `thinlens` and the
//! `projector` emitter) and a rigid `to_world` ([`rigid_to_world`], `perspective` and
//! `thinlens`).

use crate::load::props::PluginProps;
use glam::Affine3A;
use matte_scene_file::SceneError;

/// Which axis `fov` refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FovAxis {
    X,
    Y,
    Diagonal,
    Smaller,
    Larger,
}

/// tan(x_fov / 2) for `fov_deg` along `axis` on an image of aspect width/height (Mitsuba
/// `parse_fov`, `src/render/sensor.cpp`).
pub fn x_half_tan(fov_deg: f64, axis: FovAxis, aspect: f64) -> f64 {
    let half = (fov_deg.to_radians() * 0.5).tan();
    match axis {
        FovAxis::X => half,
        FovAxis::Y => half * aspect,
        FovAxis::Diagonal => half / (1.0 + 1.0 / (aspect * aspect)).sqrt(),
        FovAxis::Smaller => {
            if aspect > 1.0 {
                half * aspect
            } else {
                half
            }
        }
        FovAxis::Larger => {
            if aspect > 1.0 {
                half
            } else {
                half * aspect
            }
        }
    }
}

/// The diagonal fov in degrees of a `focal_length` in mm (on the 36×24 frame).
fn focal_length_to_diagonal_fov(mm: f64) -> f64 {
    2.0 * ((36.0f64 * 36.0 + 24.0 * 24.0).sqrt() / (2.0 * mm)).atan().to_degrees()
}

/// `ProjectiveCamera`'s properties (`src/render/sensor.cpp`): near_clip, far_clip and
/// focus_distance (default far_clip; a positive finite distance), which every sensor reads and
/// only `thinlens` uses.
pub(crate) fn clip_range(p: &mut PluginProps) -> Result<(f32, f32, f32), SceneError> {
    let near = p.positive("near_clip")? as f32;
    let far = p.positive("far_clip")? as f32;
    if far <= near {
        return Err(p.err(format!("far_clip ({far}) must exceed near_clip ({near})")));
    }
    let focus = p.float_or("focus_distance", far as f64)?;
    if !(focus > 0.0 && focus.is_finite()) {
        return Err(p.prop_err("focus_distance", format!("must be a positive distance, got {focus}")));
    }
    Ok((near, far, focus as f32))
}

/// `to_world` of `perspective` and `thinlens`: a rotation and translation.
pub(crate) fn rigid_to_world(p: &mut PluginProps) -> Result<Affine3A, SceneError> {
    let to_world = p.transform("to_world")?;
    if has_scale(&to_world) {
        return Err(p.prop_err(
            "to_world",
            "contains a scale or shear; scale factors are not allowed in a camera transform (as in Mitsuba)",
        ));
    }
    Ok(to_world)
}

/// Mitsuba's `Transform::has_scale` (`include/mitsuba/core/transform.h`), used by the
/// perspective sensor: the rows of the linear part must be orthonormal to 1e-3
/// (|Σₖ mᵢₖ mⱼₖ − δᵢⱼ| ≤ 1e-3). So a shear is a scale, and a mirror is not.
fn has_scale(m: &Affine3A) -> bool {
    let rows = [m.matrix3.row(0), m.matrix3.row(1), m.matrix3.row(2)];
    (0..3).any(|i| (i..3).any(|j| (rows[i].dot(rows[j]) - if i == j { 1.0 } else { 0.0 }).abs() > 1e-3))
}

/// The field of view as `perspective` reads it (`src/render/sensor.cpp`, `parse_fov`), also
/// read by the `projector` emitter: `fov` in degrees with `fov_axis` (default x), or
/// `focal_length` (default "50mm", a diagonal field of view), never both.
pub(crate) fn field_of_view(p: &mut PluginProps) -> Result<(f64, FovAxis), SceneError> {
    let fov = p.float_opt("fov")?;
    let focal = p.string_opt("focal_length")?;
    match (fov, focal) {
        (Some(_), Some(_)) => Err(p.err("give either fov or focal_length, not both")),
        (Some(f), None) => {
            if !(f > 0.0 && f < 180.0) {
                return Err(p.prop_err("fov", format!("must be in (0, 180) degrees, got {f}")));
            }
            Ok((f, FovAxis::from_props(p)?))
        }
        (None, _) => Ok((focal_length_to_diagonal_fov(focal_length_mm(p)?), FovAxis::Diagonal)),
    }
}

/// `focal_length` (default "50mm") in millimetres.
fn focal_length_mm(p: &mut PluginProps) -> Result<f64, SceneError> {
    let text = p.string("focal_length")?;
    text.trim()
        .strip_suffix("mm")
        .unwrap_or(&text)
        .trim()
        .parse()
        .ok()
        .filter(|v: &f64| *v > 0.0)
        .ok_or_else(|| p.prop_err("focal_length", format!("must look like \"50mm\", got \"{text}\"")))
}

impl FovAxis {
    /// `fov_axis` (default x): x, y, diagonal, smaller or larger.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        Ok(match p.string("fov_axis")?.to_lowercase().as_str() {
            "x" => FovAxis::X,
            "y" => FovAxis::Y,
            "diagonal" => FovAxis::Diagonal,
            "smaller" => FovAxis::Smaller,
            "larger" => FovAxis::Larger,
            other => {
                let message = format!("must be x, y, diagonal, smaller or larger, got \"{other}\"");
                return Err(p.prop_err("fov_axis", message));
            }
        })
    }
}
