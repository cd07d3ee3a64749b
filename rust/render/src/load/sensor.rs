//! `<sensor>`: which type builds each plugin name, and the sensor's nested film and sampler
//! (docs/renderer-semantics.md §4–6). `perspective`, `orthographic` and `thinlens` read their
//! own properties (`from_props` in their files under `rust/render/src/sensor/`, through
//! [`PluginProps`]), and so do the film (`hdrfilm`, `rust/render/src/film/mod.rs`), the
//! reconstruction filters (`rust/render/src/film/filter.rs`) and the samplers (`independent`,
//! `stratified`, `multijitter`, `orthogonal`, `ldsampler`, `rust/render/src/sampler/mod.rs`).
//! The loader attaches the film (with its filter) and the sampler to the sensor, with
//! Mitsuba's defaults when absent; a film's filter is read through
//! [`PluginProps::nested_rfilter`], here beside the dispatch.

use super::builder::{Builder, err};
use super::props::{FromProps, PluginProps};
use crate::film::{Film, ReconstructionFilter};
use crate::sampler::Sampling;
use crate::sensor::{Camera, OrthographicCamera, PerspectiveCamera, ThinLensCamera};
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

pub struct Sensor {
    pub camera: Camera,
    pub film: Film,
    pub sampling: Sampling,
}

type Constructor<T> = fn(&mut PluginProps) -> Result<T, SceneError>;

plugins! {
    /// Mitsuba 3.9.1's sensor plugins matte builds, each with its camera type.
    pub(super) NAMES, SENSORS: Constructor<Sensor> = [
        "perspective" => |p| with_film(p, PerspectiveCamera::from_props, Camera::Perspective),
        "orthographic" => |p| with_film(p, OrthographicCamera::from_props, Camera::Orthographic),
        "thinlens" => |p| with_film(p, ThinLensCamera::from_props, Camera::ThinLens),
    ];
}

plugins! {
    /// Mitsuba 3.9.1's film plugins matte builds.
    pub(super) FILM_NAMES, FILMS: Constructor<Film> = [
        "hdrfilm" => Film::from_props,
    ];
}

plugins! {
    /// Mitsuba 3.9.1's reconstruction filters, all read by [`ReconstructionFilter`]'s `from_props`.
    pub(super) RFILTER_NAMES, RFILTERS: Constructor<ReconstructionFilter> = [
        "box" => ReconstructionFilter::from_props,
        "tent" => ReconstructionFilter::from_props,
        "gaussian" => ReconstructionFilter::from_props,
        "mitchell" => ReconstructionFilter::from_props,
        "catmullrom" => ReconstructionFilter::from_props,
        "lanczos" => ReconstructionFilter::from_props,
    ];
}

plugins! {
    /// Mitsuba 3.9.1's samplers, all read by [`Sampling`]'s `from_props` (one file each under
    /// `rust/render/src/sampler/`).
    pub(super) SAMPLER_NAMES, SAMPLERS: Constructor<Sampling> = [
        "independent" => Sampling::from_props,
        "stratified" => Sampling::from_props,
        "multijitter" => Sampling::from_props,
        "orthogonal" => Sampling::from_props,
        "ldsampler" => Sampling::from_props,
    ];
}

/// The sensor of `obj`, with its film and sampler.
pub fn build(b: &Builder, obj: &SceneObject) -> Result<Sensor, SceneError> {
    build_one(b, obj, SENSORS, NAMES, "matte renders: ")
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

/// `obj` built by its entry of `table`, a family's table with its `names` (listed after `lead`
/// when `obj` is not among them); everything read.
fn build_one<T>(
    b: &Builder,
    obj: &SceneObject,
    table: &[(&str, Constructor<T>)],
    names: &[&str],
    lead: &str,
) -> Result<T, SceneError> {
    let Some(&(_, build)) = table.iter().find(|(n, _)| *n == obj.plugin) else {
        let message = format!("unsupported {} type \"{}\" ({lead}{})", obj.tag, obj.plugin, names.join(", "));
        return Err(err(obj, message));
    };
    let built = build(&mut PluginProps::new(b, obj))?;
    obj.check_all_used()?;
    Ok(built)
}

/// A `<film>`: one of [`FILM_NAMES`] ([`Film`]).
pub(super) fn build_film(b: &Builder, obj: &SceneObject) -> Result<Film, SceneError> {
    build_one(b, obj, FILMS, FILM_NAMES, "matte renders: ")
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

/// An `<rfilter>`: one of [`RFILTER_NAMES`] ([`ReconstructionFilter`]).
pub(super) fn build_rfilter(b: &Builder, obj: &SceneObject) -> Result<ReconstructionFilter, SceneError> {
    build_one(b, obj, RFILTERS, RFILTER_NAMES, "")
}

/// A `<sampler>`: one of [`SAMPLER_NAMES`] ([`Sampling`]).
pub(super) fn build_sampler(b: &Builder, obj: &SceneObject) -> Result<Sampling, SceneError> {
    build_one(b, obj, SAMPLERS, SAMPLER_NAMES, "matte renders: ")
}

impl PluginProps<'_> {
    /// Builds a film's nested `<rfilter>`, if any (at most one, and nothing else nested).
    pub fn nested_rfilter(&self) -> Result<Option<ReconstructionFilter>, SceneError> {
        film_filter(self.builder(), self.object())
    }
}
