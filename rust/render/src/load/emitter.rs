//! `<emitter>`: which type builds each plugin name. Every type reads its own properties
//! (`from_props` in its file under `rust/render/src/emitter/`, through [`PluginProps`]); the loader
//! reads what Mitsuba's `Emitter` base class reads (`sampling_weight`,
//! `src/render/emitter.cpp`) and attaches `area` emitters to their shapes.

use super::builder::{Builder, err};
use super::props::{FromProps, PluginProps};
use crate::emitter::{Area, Constant, Directional, Emitter, EnvMap, Point, Projector, Spot};
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

/// `sampling_weight` (default 1, finite and ≥ 0): the emitter's share of light samples.
fn sampling_weight(p: &mut PluginProps) -> Result<f32, SceneError> {
    let w = p.float("sampling_weight")?;
    if !(w.is_finite() && w >= 0.0) {
        return Err(p.prop_err("sampling_weight", format!("must be ≥ 0, got {w}")));
    }
    Ok(w as f32)
}

fn push(b: &mut Builder, e: Emitter, w: f32) -> u32 {
    b.emitters.push(e);
    b.sampling_weights.push(w);
    (b.emitters.len() - 1) as u32
}

/// Whether `obj` is an emitter that is built nested in a shape (`area`).
pub(super) fn in_shape(obj: &SceneObject) -> bool {
    matches!(EMITTERS.iter().find(|(n, _)| *n == obj.plugin), Some((_, Place::InShape)))
}

/// An `area` emitter nested in shape `shape`.
pub fn build_area(b: &mut Builder, obj: &SceneObject, shape: u32) -> Result<u32, SceneError> {
    if !in_shape(obj) {
        return Err(err(obj, "only an \"area\" emitter can be nested in a shape"));
    }
    let mut p = PluginProps::new(b, obj);
    let area = Area::from_props(&mut p, shape)?;
    let w = sampling_weight(&mut p)?;
    obj.check_all_used()?;
    b.area_emitters.insert(obj as *const SceneObject);
    Ok(push(b, area.into(), w))
}

type Constructor = fn(&mut PluginProps) -> Result<Emitter, SceneError>;

/// `T::from_props` as an [`Emitter`].
fn make<T: FromProps + Into<Emitter>>(p: &mut PluginProps) -> Result<Emitter, SceneError> {
    T::from_props(p).map(Into::into)
}

/// Where an emitter plugin is built.
enum Place {
    /// Nested in a shape only ([`build_area`]).
    InShape,
    /// At the top level ([`build_standalone`]), by its type.
    TopLevel(Constructor),
}

plugins! {
    /// Mitsuba 3.9.1's emitter plugins matte builds, each with where and how.
    pub(super) NAMES, EMITTERS: Place = [
        "area" => Place::InShape,
        "point" => Place::TopLevel(make::<Point>),
        "spot" => Place::TopLevel(make::<Spot>),
        "projector" => Place::TopLevel(make::<Projector>),
        "directional" => Place::TopLevel(make::<Directional>),
        "constant" => Place::TopLevel(make::<Constant>),
        "envmap" => Place::TopLevel(make::<EnvMap>),
    ];
}

/// A top-level emitter.
pub fn build_standalone(b: &mut Builder, obj: &SceneObject) -> Result<(), SceneError> {
    let constructor = match EMITTERS.iter().find(|(n, _)| *n == obj.plugin) {
        Some((_, Place::TopLevel(c))) => *c,
        Some((_, Place::InShape)) => return Err(err(obj, "an area emitter must be nested in a shape")),
        None => {
            let message = format!("unsupported emitter type \"{}\" (matte renders: {})", obj.plugin, NAMES.join(", "));
            return Err(err(obj, message));
        }
    };
    let mut p = PluginProps::new(b, obj);
    let w = sampling_weight(&mut p)?;
    let e = constructor(&mut p)?;
    obj.check_all_used()?;
    push(b, e, w);
    Ok(())
}
