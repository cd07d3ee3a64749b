//! `<sensor type="perspective">` with its `hdrfilm` (and rfilter) and sampler
//! (docs/renderer-semantics.md §4–6): fov/fov_axis or focal_length (default "50mm"), near/far clip, principal
//! point offsets, no scale in `to_world`. `<sensor type="orthographic">`
//! (`src/sensors/orthographic.cpp`): near_clip, far_clip and `to_world`, which may scale.
//! `<sensor type="thinlens">` (`src/sensors/thinlens.cpp`): as perspective without the
//! principal point, plus `aperture_radius` (required) and `focus_distance`. All three read
//! `focus_distance` (default far_clip, `ProjectiveCamera`); only `thinlens` uses it.
//! Samplers: `independent`, `stratified`, `multijitter`, `orthogonal`, `ldsampler`
//! (`src/samplers/*.cpp`) with `sample_count` rounded as each rounds it.

use super::{err, values};
use crate::camera::{Camera, FovAxis, PerspectiveCamera};
use crate::film::{CropWindow, Film, ReconstructionFilter};
use crate::orthographic::OrthographicCamera;
use crate::sampler::{SamplerKind, Sampling};
use crate::thinlens::ThinLensCamera;
use glam::Vec2;
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

pub struct Sensor {
    pub camera: Camera,
    pub film: Film,
    pub sampling: Sampling,
}

pub fn build(obj: &SceneObject) -> Result<Sensor, SceneError> {
    match obj.plugin.as_str() {
        "perspective" => build_perspective(obj),
        "orthographic" => build_orthographic(obj),
        "thinlens" => build_thinlens(obj),
        other => Err(err(
            obj,
            format!("unsupported sensor type \"{other}\" (matte renders: perspective, orthographic, thinlens)"),
        )),
    }
}

/// `ProjectiveCamera`'s properties (`src/render/sensor.cpp`): near_clip, far_clip and
/// focus_distance (default far_clip; a positive finite distance).
fn clip_range(obj: &SceneObject) -> Result<(f32, f32, f32), SceneError> {
    let near = values::positive(obj, "near_clip", 0.01)? as f32;
    let far = values::positive(obj, "far_clip", 10000.0)? as f32;
    if far <= near {
        return Err(err(obj, format!("far_clip ({far}) must exceed near_clip ({near})")));
    }
    let focus = values::float(obj, "focus_distance", far as f64)?;
    if !(focus > 0.0 && focus.is_finite()) {
        return Err(values::prop_err(obj, "focus_distance", format!("must be a positive distance, got {focus}")));
    }
    Ok((near, far, focus as f32))
}

fn build_orthographic(obj: &SceneObject) -> Result<Sensor, SceneError> {
    let to_world = values::transform(obj, "to_world")?;
    if to_world.matrix3.determinant() == 0.0 || !to_world.is_finite() {
        return Err(values::prop_err(obj, "to_world", "must be an invertible transform"));
    }
    let (near, far, _) = clip_range(obj)?;
    let (film, sampling) = film_and_sampler(obj)?;
    obj.check_all_used()?;
    let camera = Camera::Orthographic(OrthographicCamera::new(to_world, (film.width(), film.height()), near, far));
    Ok(Sensor { camera, film, sampling })
}

/// `to_world` of `perspective` and `thinlens`: a rotation and translation.
fn rigid_to_world(obj: &SceneObject) -> Result<glam::Affine3A, SceneError> {
    let to_world = values::transform(obj, "to_world")?;
    if has_scale(&to_world) {
        return Err(values::prop_err(
            obj,
            "to_world",
            "contains a scale or shear; scale factors are not allowed in a camera transform (as in Mitsuba)",
        ));
    }
    Ok(to_world)
}

fn build_perspective(obj: &SceneObject) -> Result<Sensor, SceneError> {
    let to_world = rigid_to_world(obj)?;
    let (fov_deg, axis) = field_of_view(obj)?;
    let (near, far, _) = clip_range(obj)?;
    let ppo = Vec2::new(
        principal_point_offset(obj, "principal_point_offset_x")?,
        principal_point_offset(obj, "principal_point_offset_y")?,
    );
    let (film, sampling) = film_and_sampler(obj)?;
    obj.check_all_used()?;
    let camera = PerspectiveCamera::new(to_world, fov_deg, axis, (film.width(), film.height()), ppo, near, far);
    Ok(Sensor { camera: Camera::Perspective(camera), film, sampling })
}

/// `thinlens` (`src/sensors/thinlens.cpp`): `aperture_radius` has no default in Mitsuba
/// (`props.get<float>`), 0 becomes 2⁻²⁴ there and here; matte also rejects a negative or
/// non-finite radius.
fn build_thinlens(obj: &SceneObject) -> Result<Sensor, SceneError> {
    let to_world = rigid_to_world(obj)?;
    let (fov_deg, axis) = field_of_view(obj)?;
    let (near, far, focus) = clip_range(obj)?;
    let radius = values::float_opt(obj, "aperture_radius")?
        .ok_or_else(|| err(obj, "needs the property \"aperture_radius\" (as in Mitsuba, it has no default)"))?;
    if !(radius >= 0.0 && radius.is_finite()) {
        return Err(values::prop_err(obj, "aperture_radius", format!("must be a finite radius ≥ 0, got {radius}")));
    }
    let (film, sampling) = film_and_sampler(obj)?;
    obj.check_all_used()?;
    let size = (film.width(), film.height());
    let camera = ThinLensCamera::new(to_world, fov_deg, axis, size, radius as f32, focus, near, far);
    Ok(Sensor { camera: Camera::ThinLens(camera), film, sampling })
}

/// The field of view as `perspective` reads it (`src/sensors/perspective.cpp`), also used by
/// the `projector` emitter: `fov` in degrees with `fov_axis` (default x), or `focal_length`
/// (default "50mm", a diagonal field of view), never both.
pub(super) fn field_of_view(obj: &SceneObject) -> Result<(f64, FovAxis), SceneError> {
    let fov = values::float_opt(obj, "fov")?;
    let focal = obj.properties.string("focal_length")?;
    match (fov, focal) {
        (Some(_), Some(_)) => Err(err(obj, "give either fov or focal_length, not both")),
        (Some(f), None) => {
            if !(f > 0.0 && f < 180.0) {
                return Err(values::prop_err(obj, "fov", format!("must be in (0, 180) degrees, got {f}")));
            }
            let axis = match values::string(obj, "fov_axis", "x")?.to_lowercase().as_str() {
                "x" => FovAxis::X,
                "y" => FovAxis::Y,
                "diagonal" => FovAxis::Diagonal,
                "smaller" => FovAxis::Smaller,
                "larger" => FovAxis::Larger,
                other => {
                    return Err(values::prop_err(
                        obj,
                        "fov_axis",
                        format!("must be x, y, diagonal, smaller or larger, got \"{other}\""),
                    ));
                }
            };
            Ok((f, axis))
        }
        (None, focal) => {
            let text = focal.unwrap_or_else(|| "50mm".into());
            let mm: f64 = text
                .trim()
                .strip_suffix("mm")
                .unwrap_or(&text)
                .trim()
                .parse()
                .ok()
                .filter(|v: &f64| *v > 0.0)
                .ok_or_else(|| {
                    values::prop_err(obj, "focal_length", format!("must look like \"50mm\", got \"{text}\""))
                })?;
            Ok((PerspectiveCamera::focal_length_to_diagonal_fov(mm), FovAxis::Diagonal))
        }
    }
}

/// The sensor's nested film (default: 768×576, gaussian) and sampler (default:
/// independent, 4 spp, seed 0).
fn film_and_sampler(obj: &SceneObject) -> Result<(Film, Sampling), SceneError> {
    let mut film = None;
    let mut sampler = None;
    for child in obj.children.iter() {
        child.mark_used();
        let c = &child.object;
        match c.tag.as_str() {
            // Mitsuba: "Only one film/sampler can be specified per sensor" (src/render/sensor.cpp).
            "film" if film.is_some() => {
                return Err(SceneError::at(&child.pos, "only one film can be specified per sensor"));
            }
            "sampler" if sampler.is_some() => {
                return Err(SceneError::at(&child.pos, "only one sampler can be specified per sensor"));
            }
            "film" => film = Some(build_film(c)?),
            "sampler" => sampler = Some(build_sampler(c)?),
            _ => return Err(err(c, format!("a <{}> cannot be nested in a sensor", c.tag))),
        }
    }
    let sampling = sampler.unwrap_or(Sampling::independent(4, 0));
    let film = match film {
        Some(f) => f,
        None => Film::new(768, 576, None, ReconstructionFilter::Gaussian { stddev: 0.5 }).map_err(|e| err(obj, e))?,
    };
    Ok((film, sampling))
}

/// A principal point offset (a fraction of the film size). Mitsuba takes any float; a NaN or
/// one so large that the ray direction overflows f32 would give NaN camera rays, so matte
/// requires a finite value within ±10⁶ film sizes.
fn principal_point_offset(obj: &SceneObject, name: &str) -> Result<f32, SceneError> {
    let v = values::float(obj, name, 0.0)?;
    if v.is_nan() || v.abs() > 1e6 {
        return Err(values::prop_err(
            obj,
            name,
            format!("must be a finite fraction of the film size within ±1e6, got {v}"),
        ));
    }
    Ok(v as f32)
}

pub(super) fn build_film(obj: &SceneObject) -> Result<Film, SceneError> {
    if obj.plugin != "hdrfilm" {
        return Err(err(obj, format!("unsupported film type \"{}\" (matte renders: hdrfilm)", obj.plugin)));
    }
    let width = values::integer(obj, "width", 768, 1, 1 << 16)? as u32;
    let height = values::integer(obj, "height", 576, 1, 1 << 16)? as u32;
    // Mitsuba (src/render/film.cpp): crop_width/height default to the FULL film size, not to
    // what is left after the offset, so an offset alone is an invalid crop window (§6).
    let crop =
        if ["crop_offset_x", "crop_offset_y", "crop_width", "crop_height"].iter().any(|n| obj.properties.contains(n)) {
            let ox = values::integer(obj, "crop_offset_x", 0, 0, u32::MAX as i64)? as u32;
            let oy = values::integer(obj, "crop_offset_y", 0, 0, u32::MAX as i64)? as u32;
            let w = values::integer(obj, "crop_width", width as i64, 1, u32::MAX as i64)? as u32;
            let h = values::integer(obj, "crop_height", height as i64, 1, u32::MAX as i64)? as u32;
            Some(CropWindow { offset: [ox, oy], size: [w, h] })
        } else {
            None
        };
    // Output format properties only affect files Mitsuba writes; matte always writes RGB float.
    let pf = values::string(obj, "pixel_format", "rgb")?.to_lowercase();
    if pf != "rgb" && pf != "rgba" {
        return Err(values::prop_err(obj, "pixel_format", format!("\"{pf}\" is not supported (rgb or rgba)")));
    }
    let _ = values::string(obj, "component_format", "float16")?;
    let _ = values::string(obj, "file_format", "openexr")?;
    if values::boolean(obj, "sample_border", false)? {
        return Err(values::prop_err(obj, "sample_border", "= true is not supported"));
    }
    let mut filter = None;
    for child in obj.children.iter() {
        child.mark_used();
        let c = &child.object;
        if c.tag != "rfilter" {
            return Err(err(c, format!("a <{}> cannot be nested in a film", c.tag)));
        }
        if filter.is_some() {
            // Mitsuba: "A film can only have one reconstruction filter" (src/render/film.cpp).
            return Err(SceneError::at(&child.pos, "a film can only have one reconstruction filter"));
        }
        filter = Some(build_rfilter(c)?);
    }
    obj.check_all_used()?;
    Film::new(width, height, crop, filter.unwrap_or_default()).map_err(|e| err(obj, e))
}

/// `<rfilter>`: `box`, `tent` (radius), `gaussian` (stddev), `mitchell` (B, C), `catmullrom`,
/// `lanczos` (lobes), with Mitsuba 3.9.1's defaults (`src/rfilters/*.cpp`).
pub(super) fn build_rfilter(obj: &SceneObject) -> Result<ReconstructionFilter, SceneError> {
    let filter = match obj.plugin.as_str() {
        "box" => ReconstructionFilter::Box,
        "tent" => ReconstructionFilter::Tent { radius: filter_size(obj, "radius", 1.0, 1.0)? },
        "gaussian" => ReconstructionFilter::Gaussian { stddev: filter_size(obj, "stddev", 0.5, 4.0)? },
        "mitchell" => ReconstructionFilter::Mitchell {
            b: values::finite(obj, "B", 1.0 / 3.0)? as f32,
            c: values::finite(obj, "C", 1.0 / 3.0)? as f32,
        },
        "catmullrom" => ReconstructionFilter::CatmullRom,
        "lanczos" => ReconstructionFilter::Lanczos {
            lobes: values::integer(obj, "lobes", 3, 1, MAX_FILTER_RADIUS as i64)? as u32,
        },
        other => {
            return Err(err(
                obj,
                format!("unsupported rfilter type \"{other}\" (box, tent, gaussian, mitchell, catmullrom, lanczos)"),
            ));
        }
    };
    obj.check_all_used()?;
    Ok(filter)
}

/// Widest reconstruction filter matte accepts, in pixels. Mitsuba has no limit, but every
/// image block carries a border of the filter radius on each side, so a radius like 1e30
/// cannot be allocated (and would overflow the block size).
const MAX_FILTER_RADIUS: f64 = 1024.0;

/// A filter parameter whose support radius is `radius_per_unit` times it.
fn filter_size(obj: &SceneObject, name: &str, default: f64, radius_per_unit: f64) -> Result<f32, SceneError> {
    let v = values::positive(obj, name, default)?;
    if v * radius_per_unit > MAX_FILTER_RADIUS {
        return Err(values::prop_err(
            obj,
            name,
            format!(
                "gives a filter radius of {} pixels; matte allows at most {MAX_FILTER_RADIUS}",
                v * radius_per_unit
            ),
        ));
    }
    Ok(v as f32)
}

/// Largest `sample_count` of the stratified samplers (their rounded counts then fit in u32).
const MAX_STRATIFIED_COUNT: i64 = 1 << 30;

/// Every sampler reads `sample_count` (default 4) and `seed` (default 0) (`Sampler`,
/// `src/render/sampler.cpp`); `stratified`, `multijitter` and `orthogonal` read `jitter`
/// (default true), `orthogonal` `strength` (default 2). The sample count is rounded as the
/// plugin's `set_sample_count` rounds it.
pub(super) fn build_sampler(obj: &SceneObject) -> Result<Sampling, SceneError> {
    let max_count = if obj.plugin == "independent" { u32::MAX as i64 } else { MAX_STRATIFIED_COUNT };
    let kind = match obj.plugin.as_str() {
        "independent" => SamplerKind::Independent,
        "stratified" => SamplerKind::Stratified { jitter: values::boolean(obj, "jitter", true)? },
        "multijitter" => SamplerKind::Multijitter { jitter: values::boolean(obj, "jitter", true)? },
        "orthogonal" => {
            let jitter = values::boolean(obj, "jitter", true)?;
            let strength = values::integer(obj, "strength", 2, 1, 32)? as u32;
            SamplerKind::Orthogonal { jitter, strength }
        }
        "ldsampler" => SamplerKind::LowDiscrepancy,
        other => {
            return Err(err(
                obj,
                format!(
                    "unsupported sampler type \"{other}\" (matte renders: independent, stratified, multijitter, \
                     orthogonal, ldsampler)"
                ),
            ));
        }
    };
    let spp = values::integer(obj, "sample_count", 4, 1, max_count)? as u32;
    let seed = values::integer(obj, "seed", 0, 0, i64::MAX)? as u64;
    obj.check_all_used()?;
    let sampling = Sampling::new(kind, spp, seed);
    if let SamplerKind::Orthogonal { strength, .. } = kind {
        let r = (sampling.spp as f64).sqrt().round() as u32;
        if strength != 2 && r.checked_pow(strength).is_none() {
            return Err(values::prop_err(
                obj,
                "strength",
                format!(
                    "{strength} with sample_count {} needs {r}^{strength} array rows, more than 2^32",
                    sampling.spp
                ),
            ));
        }
    }
    Ok(sampling)
}

/// Mitsuba's `Transform::has_scale` (`include/mitsuba/core/transform.h`), used by the
/// perspective sensor: the rows of the linear part must be orthonormal to 1e-3
/// (|Σₖ mᵢₖ mⱼₖ − δᵢⱼ| ≤ 1e-3). So a shear is a scale, and a mirror is not.
fn has_scale(m: &glam::Affine3A) -> bool {
    let rows = [m.matrix3.row(0), m.matrix3.row(1), m.matrix3.row(2)];
    (0..3).any(|i| (i..3).any(|j| (rows[i].dot(rows[j]) - if i == j { 1.0 } else { 0.0 }).abs() > 1e-3))
}
