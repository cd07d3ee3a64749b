//! Mitsuba XML object tree (`matte_scene_file::xml`) → a renderable scene. One file per plugin
//! family, each reading exactly the properties Mitsuba 3.9.1's plugin reads, with its
//! defaults; whatever is left unread is an error naming file, line and property (Mitsuba
//! does the same: `unused_properties = Error`). Each family declares its plugin names once,
//! with what builds each ([`plugins!`]): its dispatch looks names up there, and
//! [`MITSUBA_PLUGINS`] is assembled from the families' lists.

/// Declares a plugin family once: `$table`, each Mitsuba plugin name with what builds it, in
/// the order the family's error messages list them (its dispatch looks names up there), and
/// `$names`, the names alone (the family's entry of [`MITSUBA_PLUGINS`]).
macro_rules! plugins {
    (
        $(#[$doc:meta])*
        $vis:vis $names:ident, $table:ident: $entry:ty = [$($name:literal => $build:expr),+ $(,)?];
    ) => {
        $(#[$doc])*
        const $table: &[(&str, $entry)] = &[$(($name, $build)),+];

        #[doc = concat!("The plugin names of `", stringify!($table), "`, in its order.")]
        $vis const $names: &[&str] = &[$($name),+];
    };
}

pub(crate) mod bsdf;
mod builder;
mod emitter;
mod instance;
mod integrator;
#[allow(clippy::all)] // generated data (validation/generators/harvest_mitsuba_properties.py)
#[rustfmt::skip]
pub mod mitsuba_plugins;
pub mod no_effect;
pub(crate) mod props;
pub mod scope;
pub(crate) mod sensor;
mod shape;
mod walk_rays;
pub use walk_rays::WALK_BOUNCES;
pub(crate) mod texture;

use builder::Builder;
pub(crate) use builder::err;
pub use builder::{LoadedScene, set_package_folder};

use crate::emitter::Emitter;
use crate::integrator::Integrator;
use crate::scene::Scene;
use crate::sensor::Camera;
use glam::Affine3A;
use matte_scene_file::SceneError;
use matte_scene_file::xml::{self, SceneObject};
use std::collections::HashMap;
use std::path::Path;
use std::rc::Rc;

/// The Mitsuba 3.9.1 plugins matte's renderer builds, by element tag (`"scene"`: the root's
/// own properties), each family's list as its file declares it. Every property each of them
/// reads in Mitsuba's sources ([`mitsuba_plugins`]) is implemented by its builder here or
/// accepted as one that cannot change the image ([`no_effect`]); `tests/render/load/walk.rs`
/// walks the list. matte's own BSDFs (the registered types, `matte_brdf::BSDF_TYPES`: the
/// diffuse models and `tabulated_brdf`) come on top; what is refused by scope is in [`scope`].
pub const MITSUBA_PLUGINS: &[(&str, &[&str])] = &[
    ("scene", &["scene"]),
    ("bsdf", bsdf::MITSUBA_NAMES),
    ("emitter", emitter::NAMES),
    ("film", sensor::FILM_NAMES),
    ("integrator", integrator::NAMES),
    ("rfilter", sensor::RFILTER_NAMES),
    ("sampler", sensor::SAMPLER_NAMES),
    ("sensor", sensor::NAMES),
    ("shape", shape::NAMES),
    ("texture", texture::NAMES),
    // Only as the `volume` of a `volume` texture, or declared at the top level ([`scope`]).
    ("volume", texture::VOLUME_NAMES),
];

/// Parses and builds the scene at `path` with `-D name=value` overrides.
pub fn load_file(path: &Path, overrides: &[(String, String)]) -> Result<LoadedScene, SceneError> {
    let root = xml::parse_file(path, overrides)?;
    build(&root, path)
}

/// Builds from an XML string; relative file names resolve against `path`'s folder.
pub fn load_str(text: &str, path: &Path, overrides: &[(String, String)]) -> Result<LoadedScene, SceneError> {
    let root = xml::parse_str(text, path, overrides)?;
    build(&root, path)
}

fn build(root: &Rc<SceneObject>, path: &Path) -> Result<LoadedScene, SceneError> {
    let mut b = Builder {
        base_dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
        search_paths: root.search_paths.clone(),
        bsdfs: Vec::new(),
        bsdf_index: HashMap::new(),
        shapes: Vec::new(),
        emitters: Vec::new(),
        sampling_weights: Vec::new(),
        shape: None,
        shape_dependent: std::cell::Cell::new(false),
        shape_dependent_bsdfs: std::collections::HashSet::new(),
        area_emitters: std::collections::HashSet::new(),
    };
    scope::check_tree(root)?;
    let mut notes = no_effect::accept_tree(root)?;
    let mut integrator = None;
    let mut integrator_obj = None;
    let mut sensor = None;
    let mut top_level_area = Vec::new();
    // Mitsuba's `Scene` constructor (`src/render/scene.cpp`) takes any object at the top
    // level: shapes, emitters, sensors and the integrator make the scene; every other object
    // (a BSDF, texture, volume, sampler, film, filter declared with an id for `<ref>`s) is
    // instantiated, so its properties are checked, and otherwise unused.
    for child in &root.children {
        child.mark_used();
        let obj = &child.object;
        match obj.tag.as_str() {
            "integrator" => {
                if integrator.is_some() {
                    return Err(SceneError::at(&obj.pos, "only one integrator can be specified per scene"));
                }
                integrator = Some(integrator::build(&b, obj)?);
                integrator_obj = Some(obj.clone());
            }
            "sensor" => {
                // Every sensor is built (and so checked); `mi.render(scene)` renders the first
                // in document order, and so does matte.
                let built = sensor::build(&b, obj)?;
                if sensor.is_none() {
                    sensor = Some(built);
                } else {
                    notes.push(format!(
                        "{}: the scene has more than one <sensor>; matte renders the first, as mi.render(scene) does",
                        obj.pos
                    ));
                }
            }
            // `shapegroup` and `instance` are built on the shapes they hold ([`instance`]).
            "shape" => match shape::how(obj) {
                Some(shape::How::Group) => instance::check_group(obj)?,
                Some(shape::How::Instance) => instance::build(&mut b, obj)?,
                _ => shape::build_placed(&mut b, obj, Affine3A::IDENTITY, false)?,
            },
            // An area emitter declared at the top level is built by the shapes that `<ref>` it.
            "emitter" if emitter::in_shape(obj) => top_level_area.push(obj.clone()),
            "emitter" => {
                if (obj.plugin == "constant" || obj.plugin == "envmap")
                    && b.emitters.iter().any(Emitter::is_environment)
                {
                    return Err(SceneError::at(&obj.pos, "only one environment emitter (constant, envmap) is allowed"));
                }
                emitter::build_standalone(&mut b, obj)?
            }
            "bsdf" => {
                bsdf::get_or_build(&mut b, obj)?;
            }
            "texture" => {
                texture::build(&b, obj)?;
            }
            // Declared for a `volume` texture to `<ref>` (scope allows it here and there only).
            "volume" => {
                texture::build_volume(&b, obj)?;
            }
            "sampler" => {
                sensor::build_sampler(&b, obj)?;
            }
            "film" => {
                sensor::build_film(&b, obj)?;
            }
            "rfilter" => {
                sensor::build_rfilter(&b, obj)?;
            }
            other => {
                return Err(SceneError::at(&obj.pos, format!("<{other}> is not allowed at the top level of a scene")));
            }
        }
    }
    // One that no shape uses emits nothing (as in Mitsuba); it is still checked.
    for obj in top_level_area {
        if !b.area_emitters.contains(&Rc::as_ptr(&obj)) {
            emitter::build_area(&mut b, &obj, 0)?;
            b.emitters.pop();
            b.sampling_weights.pop();
        }
    }
    root.check_all_used()?;
    let sensor = sensor.ok_or_else(|| SceneError::at(&root.pos, "the scene has no <sensor>"))?;
    let integrator = match integrator {
        Some(i) => i,
        // Mitsuba's default integrator.
        None => Integrator::Path(crate::integrator::PathIntegrator {
            max_depth: u32::MAX,
            rr_depth: 5,
            hide_emitters: false,
        }),
    };
    if let (Integrator::ParticleTracer(_), Some(obj)) = (&integrator, &integrator_obj) {
        particle_tracer_limits(&b, &sensor, obj)?;
    }
    into_mitsuba_emitter_order(&mut b);
    let scene = Scene::new(b.shapes, b.bsdfs, b.emitters, b.sampling_weights);
    Ok(LoadedScene { scene, camera: sensor.camera, film: sensor.film, integrator, sampling: sensor.sampling, notes })
}

/// What matte's `ptracer` does not support, as load errors at the integrator: other sensors
/// than `perspective`, other filters than `box`, emitters without `sample_ray` (environment,
/// directional, area lights on analytic shapes), BSDFs that refract (matte evaluates BSDFs
/// for radiance only; importance transport differs by η² there).
fn particle_tracer_limits(b: &Builder, sensor: &sensor::Sensor, obj: &SceneObject) -> Result<(), SceneError> {
    use crate::bsdf::{BsdfFlags, Bxdf};
    use crate::emitter::Light;
    if !matches!(sensor.camera, Camera::Perspective(_)) {
        return Err(err(obj, "matte's ptracer needs a perspective sensor (not orthographic or thinlens)"));
    }
    if !matches!(sensor.film.filter(), crate::film::ReconstructionFilter::Box) {
        return Err(err(obj, "matte's ptracer needs the box reconstruction filter (rfilter type=\"box\")"));
    }
    if b.emitters.iter().any(|e| !e.can_sample_ray(&b.shapes)) {
        return Err(err(obj, "matte's ptracer supports area (on meshes), point, spot and projector emitters only"));
    }
    // Refraction is Mitsuba's `NonSymmetric` flag.
    if b.bsdfs.iter().any(|bsdf| bsdf.flags().has(BsdfFlags::NON_SYMMETRIC)) {
        return Err(err(obj, "matte's ptracer does not support refracting BSDFs (dielectrics, principled spec_trans)"));
    }
    Ok(())
}

/// Puts the emitters in the order of Mitsuba 3.9.1's `Scene::emitters()`, which emitter
/// selection lays on [0, 1): the top-level emitters and the area emitters of analytic shapes in
/// declaration order, then those of meshes (`obj`, `ply`, `serialized`, `rectangle`, `cube`)
/// last, in reverse declaration order (its parser's mesh merging, `src/core/parser.cpp`,
/// `src/shapes/merge.cpp`; measured with `load_file(..., parallel=False)`: with parallel
/// loading, the default, the mesh emitters' order among themselves varies from run to run).
/// Only `ldsampler`'s expectation depends on it (docs/renderer-semantics.md §5).
fn into_mitsuba_emitter_order(b: &mut Builder) {
    use crate::shape::Geometry;
    let emitters = std::mem::take(&mut b.emitters);
    let weights = std::mem::take(&mut b.sampling_weights);
    let mut items: Vec<(usize, Emitter, f32)> =
        emitters.into_iter().zip(weights).enumerate().map(|(i, (e, w))| (i, e, w)).collect();
    // Analytic first by declaration (key 0, i); meshes after, reversed (key 1, −i).
    items.sort_by_key(|(i, e, _)| match e.area_shape() {
        Some(shape) if matches!(b.shapes[shape as usize].geometry, Geometry::Triangles(_)) => (1, -(*i as i64)),
        _ => (0, *i as i64),
    });
    let mut new_index = vec![0u32; items.len()];
    for (new, (old, ..)) in items.iter().enumerate() {
        new_index[*old] = new as u32;
    }
    for shape in &mut b.shapes {
        shape.emitter = shape.emitter.map(|e| new_index[e as usize]);
    }
    (b.emitters, b.sampling_weights) = items.into_iter().map(|(_, e, w)| (e, w)).unzip();
}
