//! `<sensor>`: which type builds each plugin name, and the sensor's nested film and sampler
//! (docs/renderer-semantics.md §4–6). `perspective`, `orthographic` and `thinlens` read their
//! own properties (`from_props` in `rust/render/src/camera.rs`, `orthographic.rs`, `thinlens.rs`,
//! through [`PluginProps`]), and so do the film (`hdrfilm`, `rust/render/src/film/mod.rs`), the
//! reconstruction filters (`rust/render/src/film/filter.rs`) and the samplers (`independent`,
//! `stratified`, `multijitter`, `orthogonal`, `ldsampler`, `rust/render/src/sampler.rs`). The loader
//! attaches the film (with its filter) and the sampler to the sensor, with Mitsuba's defaults
//! when absent.

use super::props::{FromProps, PluginProps};
use super::{Builder, err};
use crate::camera::{Camera, PerspectiveCamera};
use crate::film::{Film, ReconstructionFilter};
use crate::orthographic::OrthographicCamera;
use crate::sampler::Sampling;
use crate::thinlens::ThinLensCamera;
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

pub struct Sensor {
    pub camera: Camera,
    pub film: Film,
    pub sampling: Sampling,
}

/// The sensor of `obj`, with its film and sampler.
pub fn build(b: &Builder, obj: &SceneObject) -> Result<Sensor, SceneError> {
    const NAMES: [&str; 3] = ["perspective", "orthographic", "thinlens"];
    if !NAMES.contains(&obj.plugin.as_str()) {
        let message = format!("unsupported sensor type \"{}\" (matte renders: {})", obj.plugin, NAMES.join(", "));
        return Err(err(obj, message));
    }
    let p = &mut PluginProps::new(b, obj);
    let sensor = match obj.plugin.as_str() {
        "orthographic" => with_film(p, OrthographicCamera::from_props, Camera::Orthographic),
        "thinlens" => with_film(p, ThinLensCamera::from_props, Camera::ThinLens),
        _ => with_film(p, PerspectiveCamera::from_props, Camera::Perspective),
    }?;
    obj.check_all_used()?;
    Ok(sensor)
}

/// The camera `read` reads, made for the size of the film read after it.
fn with_film<C, F: FnOnce((u32, u32)) -> C>(
    p: &mut PluginProps,
    read: fn(&mut PluginProps) -> Result<F, SceneError>,
    camera: fn(C) -> Camera,
) -> Result<Sensor, SceneError> {
    let for_film = read(p)?;
    let (film, sampling) = film_and_sampler(p)?;
    let camera = camera(for_film((film.width(), film.height())));
    Ok(Sensor { camera, film, sampling })
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

/// `T::from_props` for `obj`, a plugin among `names` (listed after `lead` when it is not);
/// everything read.
fn build_one<T: FromProps>(b: &Builder, obj: &SceneObject, names: &[&str], lead: &str) -> Result<T, SceneError> {
    if !names.contains(&obj.plugin.as_str()) {
        let message = format!("unsupported {} type \"{}\" ({lead}{})", obj.tag, obj.plugin, names.join(", "));
        return Err(err(obj, message));
    }
    let built = T::from_props(&mut PluginProps::new(b, obj))?;
    obj.check_all_used()?;
    Ok(built)
}

/// A `<film>`: `hdrfilm` ([`Film`]).
pub(super) fn build_film(b: &Builder, obj: &SceneObject) -> Result<Film, SceneError> {
    build_one(b, obj, &["hdrfilm"], "matte renders: ")
}

/// The film's nested reconstruction filter, if any (at most one).
pub(super) fn film_filter(b: &Builder, obj: &SceneObject) -> Result<Option<ReconstructionFilter>, SceneError> {
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

/// An `<rfilter>` ([`ReconstructionFilter`]).
pub(super) fn build_rfilter(b: &Builder, obj: &SceneObject) -> Result<ReconstructionFilter, SceneError> {
    build_one(b, obj, &["box", "tent", "gaussian", "mitchell", "catmullrom", "lanczos"], "")
}

/// A `<sampler>` ([`Sampling`]).
pub(super) fn build_sampler(b: &Builder, obj: &SceneObject) -> Result<Sampling, SceneError> {
    let names = ["independent", "stratified", "multijitter", "orthogonal", "ldsampler"];
    build_one(b, obj, &names, "matte renders: ")
}
