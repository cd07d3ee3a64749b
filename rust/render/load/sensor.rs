//! `<sensor type="perspective">` with its `hdrfilm` (and rfilter) and sampler
//! (docs/renderer-semantics.md §4–6): fov/fov_axis or focal_length (default "50mm"), near/far clip, principal
//! point offsets, no scale in `to_world`. `<sensor type="orthographic">`
//! (`src/sensors/orthographic.cpp`): near_clip, far_clip and `to_world`, which may scale.
//! `<sensor type="thinlens">` (`src/sensors/thinlens.cpp`): as perspective without the
//! principal point, plus `aperture_radius` (required) and `focus_distance`. All three read
//! `focus_distance` (default far_clip, `ProjectiveCamera`); only `thinlens` uses it.
//! Samplers: `independent`, `stratified`, `multijitter`, `orthogonal`, `ldsampler`
//! (`src/samplers/*.cpp`) with `sample_count` rounded as each rounds it.

use super::props::PluginProps;
use super::{Builder, err};
use crate::camera::{Camera, FovAxis, PerspectiveCamera};
use crate::film::{CropWindow, Film, ReconstructionFilter};
use crate::orthographic::OrthographicCamera;
use crate::sampler::{SamplerKind, Sampling};
use crate::thinlens::ThinLensCamera;
use glam::{Affine3A, Vec2};
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

pub struct Sensor {
    pub camera: Camera,
    pub film: Film,
    pub sampling: Sampling,
}

/// The sensor of `obj`, with its film and sampler.
pub fn build(b: &Builder, obj: &SceneObject) -> Result<Sensor, SceneError> {
    let build: fn(&mut PluginProps) -> Result<Sensor, SceneError> = match obj.plugin.as_str() {
        "perspective" => perspective,
        "orthographic" => orthographic,
        "thinlens" => thinlens,
        other => {
            return Err(err(
                obj,
                format!("unsupported sensor type \"{other}\" (matte renders: perspective, orthographic, thinlens)"),
            ));
        }
    };
    let sensor = build(&mut PluginProps::new(b, obj))?;
    obj.check_all_used()?;
    Ok(sensor)
}

/// `ProjectiveCamera`'s properties (`src/render/sensor.cpp`): near_clip, far_clip and
/// focus_distance (default far_clip; a positive finite distance).
fn clip_range(p: &mut PluginProps) -> Result<(f32, f32, f32), SceneError> {
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

/// `orthographic` (`src/sensors/orthographic.cpp`): `to_world` may scale, but must be
/// invertible.
fn orthographic(p: &mut PluginProps) -> Result<Sensor, SceneError> {
    let to_world = p.transform("to_world")?;
    if to_world.matrix3.determinant() == 0.0 || !to_world.is_finite() {
        return Err(p.prop_err("to_world", "must be an invertible transform"));
    }
    let (near, far, _) = clip_range(p)?;
    let (film, sampling) = film_and_sampler(p)?;
    let camera = Camera::Orthographic(OrthographicCamera::new(to_world, (film.width(), film.height()), near, far));
    Ok(Sensor { camera, film, sampling })
}

/// `to_world` of `perspective` and `thinlens`: a rotation and translation.
fn rigid_to_world(p: &mut PluginProps) -> Result<Affine3A, SceneError> {
    let to_world = p.transform("to_world")?;
    if has_scale(&to_world) {
        return Err(p.prop_err(
            "to_world",
            "contains a scale or shear; scale factors are not allowed in a camera transform (as in Mitsuba)",
        ));
    }
    Ok(to_world)
}

/// `perspective` (`src/sensors/perspective.cpp`).
fn perspective(p: &mut PluginProps) -> Result<Sensor, SceneError> {
    let to_world = rigid_to_world(p)?;
    let (fov_deg, axis) = field_of_view(p)?;
    let (near, far, _) = clip_range(p)?;
    let ppo = Vec2::new(
        principal_point_offset(p, "principal_point_offset_x")?,
        principal_point_offset(p, "principal_point_offset_y")?,
    );
    let (film, sampling) = film_and_sampler(p)?;
    let camera = PerspectiveCamera::new(to_world, fov_deg, axis, (film.width(), film.height()), ppo, near, far);
    Ok(Sensor { camera: Camera::Perspective(camera), film, sampling })
}

/// `thinlens` (`src/sensors/thinlens.cpp`): `aperture_radius` has no default in Mitsuba
/// (`props.get<float>`), 0 becomes 2⁻²⁴ there and here; matte also rejects a negative or
/// non-finite radius.
fn thinlens(p: &mut PluginProps) -> Result<Sensor, SceneError> {
    let to_world = rigid_to_world(p)?;
    let (fov_deg, axis) = field_of_view(p)?;
    let (near, far, focus) = clip_range(p)?;
    let radius = p
        .float_opt("aperture_radius")?
        .ok_or_else(|| p.err("needs the property \"aperture_radius\" (as in Mitsuba, it has no default)"))?;
    if !(radius >= 0.0 && radius.is_finite()) {
        return Err(p.prop_err("aperture_radius", format!("must be a finite radius ≥ 0, got {radius}")));
    }
    let (film, sampling) = film_and_sampler(p)?;
    let size = (film.width(), film.height());
    let camera = ThinLensCamera::new(to_world, fov_deg, axis, size, radius as f32, focus, near, far);
    Ok(Sensor { camera: Camera::ThinLens(camera), film, sampling })
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
            Ok((f, fov_axis(p)?))
        }
        (None, _) => {
            let text = p.string("focal_length")?;
            let mm: f64 = text
                .trim()
                .strip_suffix("mm")
                .unwrap_or(&text)
                .trim()
                .parse()
                .ok()
                .filter(|v: &f64| *v > 0.0)
                .ok_or_else(|| p.prop_err("focal_length", format!("must look like \"50mm\", got \"{text}\"")))?;
            Ok((PerspectiveCamera::focal_length_to_diagonal_fov(mm), FovAxis::Diagonal))
        }
    }
}

/// `fov_axis` (default x): x, y, diagonal, smaller or larger.
fn fov_axis(p: &mut PluginProps) -> Result<FovAxis, SceneError> {
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

/// The sensor's nested film (default: 768×576, gaussian) and sampler (default:
/// independent, 4 spp, seed 0).
fn film_and_sampler(p: &mut PluginProps) -> Result<(Film, Sampling), SceneError> {
    let (b, obj) = (p.builder(), p.object());
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
            "film" => film = Some(build_film(b, c)?),
            "sampler" => sampler = Some(build_sampler(b, c)?),
            _ => return Err(err(c, format!("a <{}> cannot be nested in a sensor", c.tag))),
        }
    }
    let sampling = sampler.unwrap_or(Sampling::independent(4, 0));
    let film = match film {
        Some(f) => f,
        None => Film::new(768, 576, None, ReconstructionFilter::Gaussian { stddev: 0.5 }).map_err(|e| p.err(e))?,
    };
    Ok((film, sampling))
}

/// A principal point offset (a fraction of the film size). Mitsuba takes any float; a NaN or
/// one so large that the ray direction overflows f32 would give NaN camera rays, so matte
/// requires a finite value within ±10⁶ film sizes.
fn principal_point_offset(p: &mut PluginProps, name: &str) -> Result<f32, SceneError> {
    let v = p.float(name)?;
    if v.is_nan() || v.abs() > 1e6 {
        return Err(p.prop_err(name, format!("must be a finite fraction of the film size within ±1e6, got {v}")));
    }
    Ok(v as f32)
}

/// `<film type="hdrfilm">` (`src/films/hdrfilm.cpp`, the `Film` base class).
pub(super) fn build_film(b: &Builder, obj: &SceneObject) -> Result<Film, SceneError> {
    if obj.plugin != "hdrfilm" {
        return Err(err(obj, format!("unsupported film type \"{}\" (matte renders: hdrfilm)", obj.plugin)));
    }
    let p = &mut PluginProps::new(b, obj);
    // Mitsuba's defaults are `is_m_film ? 1 : 768` and `… : 576`: an hdrfilm is not an m-film.
    let width = p.integer_or("width", 768, 1..=1 << 16)? as u32;
    let height = p.integer_or("height", 576, 1..=1 << 16)? as u32;
    let crop = crop_window(p, width, height)?;
    // Output format properties only affect files Mitsuba writes; matte always writes RGB float.
    let pf = p.string("pixel_format")?.to_lowercase();
    if pf != "rgb" && pf != "rgba" {
        return Err(p.prop_err("pixel_format", format!("\"{pf}\" is not supported (rgb or rgba)")));
    }
    let _ = p.string("component_format")?;
    let _ = p.string("file_format")?;
    if p.boolean("sample_border")? {
        return Err(p.prop_err("sample_border", "= true is not supported"));
    }
    let filter = film_filter(b, obj)?;
    obj.check_all_used()?;
    Film::new(width, height, crop, filter.unwrap_or_default()).map_err(|e| err(obj, e))
}

/// The crop window, if any crop property is given. Mitsuba (src/render/film.cpp):
/// crop_width/height default to the FULL film size, not to what is left after the offset, so
/// an offset alone is an invalid crop window (docs/renderer-semantics.md §6).
fn crop_window(p: &mut PluginProps, width: u32, height: u32) -> Result<Option<CropWindow>, SceneError> {
    if !["crop_offset_x", "crop_offset_y", "crop_width", "crop_height"].iter().any(|n| p.has_property(n)) {
        return Ok(None);
    }
    let ox = p.integer("crop_offset_x", 0..=u32::MAX as i64)? as u32;
    let oy = p.integer("crop_offset_y", 0..=u32::MAX as i64)? as u32;
    let w = p.integer_or("crop_width", width as i64, 1..=u32::MAX as i64)? as u32;
    let h = p.integer_or("crop_height", height as i64, 1..=u32::MAX as i64)? as u32;
    Ok(Some(CropWindow { offset: [ox, oy], size: [w, h] }))
}

/// The film's nested reconstruction filter, if any (at most one).
fn film_filter(b: &Builder, obj: &SceneObject) -> Result<Option<ReconstructionFilter>, SceneError> {
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
        filter = Some(build_rfilter(b, c)?);
    }
    Ok(filter)
}

/// `<rfilter>`: `box`, `tent` (radius), `gaussian` (stddev), `mitchell` (B, C), `catmullrom`,
/// `lanczos` (lobes), with Mitsuba 3.9.1's defaults (`src/rfilters/*.cpp`).
pub(super) fn build_rfilter(b: &Builder, obj: &SceneObject) -> Result<ReconstructionFilter, SceneError> {
    const NAMES: [&str; 6] = ["box", "tent", "gaussian", "mitchell", "catmullrom", "lanczos"];
    if !NAMES.contains(&obj.plugin.as_str()) {
        let message = format!("unsupported rfilter type \"{}\" ({})", obj.plugin, NAMES.join(", "));
        return Err(err(obj, message));
    }
    let p = &mut PluginProps::new(b, obj);
    let filter = match obj.plugin.as_str() {
        "tent" => ReconstructionFilter::Tent { radius: filter_size(p, "radius", 1.0)? },
        "gaussian" => ReconstructionFilter::Gaussian { stddev: filter_size(p, "stddev", 4.0)? },
        // Mitsuba's defaults are `1.f / 3.f`.
        "mitchell" => ReconstructionFilter::Mitchell {
            b: p.finite_or("B", 1.0 / 3.0)? as f32,
            c: p.finite_or("C", 1.0 / 3.0)? as f32,
        },
        "catmullrom" => ReconstructionFilter::CatmullRom,
        "lanczos" => ReconstructionFilter::Lanczos { lobes: p.integer("lobes", 1..=MAX_FILTER_RADIUS as i64)? as u32 },
        _ => ReconstructionFilter::Box,
    };
    obj.check_all_used()?;
    Ok(filter)
}

/// Widest reconstruction filter matte accepts, in pixels. Mitsuba has no limit, but every
/// image block carries a border of the filter radius on each side, so a radius like 1e30
/// cannot be allocated (and would overflow the block size).
const MAX_FILTER_RADIUS: f64 = 1024.0;

/// A filter parameter (positive, the harvested default) whose support radius is
/// `radius_per_unit` times it.
fn filter_size(p: &mut PluginProps, name: &str, radius_per_unit: f64) -> Result<f32, SceneError> {
    let v = p.positive(name)?;
    if v * radius_per_unit > MAX_FILTER_RADIUS {
        let radius = v * radius_per_unit;
        let message = format!("gives a filter radius of {radius} pixels; matte allows at most {MAX_FILTER_RADIUS}");
        return Err(p.prop_err(name, message));
    }
    Ok(v as f32)
}

/// Largest `sample_count` of the stratified samplers (their rounded counts then fit in u32).
const MAX_STRATIFIED_COUNT: i64 = 1 << 30;

/// Every sampler reads `sample_count` (default 4) and `seed` (default 0) (`Sampler`,
/// `src/render/sampler.cpp`); `stratified`, `multijitter` and `orthogonal` read `jitter`
/// (default true), `orthogonal` `strength` (default 2). The sample count is rounded as the
/// plugin's `set_sample_count` rounds it.
pub(super) fn build_sampler(b: &Builder, obj: &SceneObject) -> Result<Sampling, SceneError> {
    const NAMES: [&str; 5] = ["independent", "stratified", "multijitter", "orthogonal", "ldsampler"];
    if !NAMES.contains(&obj.plugin.as_str()) {
        let message = format!("unsupported sampler type \"{}\" (matte renders: {})", obj.plugin, NAMES.join(", "));
        return Err(err(obj, message));
    }
    let p = &mut PluginProps::new(b, obj);
    let max_count = if obj.plugin == "independent" { u32::MAX as i64 } else { MAX_STRATIFIED_COUNT };
    let kind = match obj.plugin.as_str() {
        "stratified" => SamplerKind::Stratified { jitter: p.boolean("jitter")? },
        "multijitter" => SamplerKind::Multijitter { jitter: p.boolean("jitter")? },
        "orthogonal" => {
            let jitter = p.boolean("jitter")?;
            SamplerKind::Orthogonal { jitter, strength: p.integer("strength", 1..=32)? as u32 }
        }
        "ldsampler" => SamplerKind::LowDiscrepancy,
        _ => SamplerKind::Independent,
    };
    let spp = p.integer("sample_count", 1..=max_count)? as u32;
    let seed = p.integer("seed", 0..=i64::MAX)? as u64;
    obj.check_all_used()?;
    let sampling = Sampling::new(kind, spp, seed);
    if let SamplerKind::Orthogonal { strength, .. } = kind {
        let r = (sampling.spp as f64).sqrt().round() as u32;
        if strength != 2 && r.checked_pow(strength).is_none() {
            let message = format!(
                "{strength} with sample_count {} needs {r}^{strength} array rows, more than 2^32",
                sampling.spp
            );
            return Err(p.prop_err("strength", message));
        }
    }
    Ok(sampling)
}

/// Mitsuba's `Transform::has_scale` (`include/mitsuba/core/transform.h`), used by the
/// perspective sensor: the rows of the linear part must be orthonormal to 1e-3
/// (|Σₖ mᵢₖ mⱼₖ − δᵢⱼ| ≤ 1e-3). So a shear is a scale, and a mirror is not.
fn has_scale(m: &Affine3A) -> bool {
    let rows = [m.matrix3.row(0), m.matrix3.row(1), m.matrix3.row(2)];
    (0..3).any(|i| (i..3).any(|j| (rows[i].dot(rows[j]) - if i == j { 1.0 } else { 0.0 }).abs() > 1e-3))
}
