//! Mitsuba XML object tree (`matte_scene_file::xml`) → a renderable scene. One file per plugin
//! family, each reading exactly the properties Mitsuba 3.9.1's plugin reads, with its
//! defaults; whatever is left unread is an error naming file, line and property (Mitsuba
//! does the same: `unused_properties = Error`).

pub(crate) mod bsdf;
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

use crate::camera::Camera;
use crate::emitter::Emitter;
use crate::film::Film;
use crate::integrator::Integrator;
use crate::sampler::Sampling;
use crate::scene::Scene;
use matte_scene_file::SceneError;
use matte_scene_file::xml::{self, SceneObject};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// The Mitsuba 3.9.1 plugins matte's renderer builds, by element tag (`"scene"`: the root's
/// own properties). Every property each of them reads in Mitsuba's sources
/// ([`mitsuba_plugins`]) is implemented by its builder here or accepted as one that cannot
/// change the image ([`no_effect`]); `tests/render/load.rs` walks the list. matte's own BSDFs
/// (the registered types, `matte_brdf::BSDF_TYPES`: the diffuse models and `tabulated_brdf`)
/// come on top; what is refused by scope is in [`scope`].
pub const MITSUBA_PLUGINS: &[(&str, &[&str])] = &[
    ("scene", &["scene"]),
    ("bsdf", &bsdf::MITSUBA_NAMES),
    ("emitter", &["area", "constant", "directional", "envmap", "point", "projector", "spot"]),
    ("film", &["hdrfilm"]),
    ("integrator", &["direct", "moment", "path", "ptracer", "volpath", "volpathmis"]),
    ("rfilter", &["box", "catmullrom", "gaussian", "lanczos", "mitchell", "tent"]),
    ("sampler", &["independent", "ldsampler", "multijitter", "orthogonal", "stratified"]),
    ("sensor", &["orthographic", "perspective", "thinlens"]),
    (
        "shape",
        &["cube", "cylinder", "disk", "instance", "obj", "ply", "rectangle", "serialized", "shapegroup", "sphere"],
    ),
    ("texture", &["bitmap", "checkerboard", "mesh_attribute", "rawconstant", "volume"]),
    // Only as the `volume` of a `volume` texture, or declared at the top level ([`scope`]).
    ("volume", &["constvolume", "gridvolume"]),
];

/// Everything `matte render` needs.
pub struct LoadedScene {
    pub scene: Scene,
    pub camera: Camera,
    /// A fresh film (size, crop, filter) to render into.
    pub film: Film,
    pub integrator: Integrator,
    /// The sensor's sampler: its kind, `sample_count` (rounded as Mitsuba rounds it) and
    /// `seed`.
    pub sampling: Sampling,
    /// What the user should know about how the scene was read (one line each, for stderr):
    /// e.g. which of several sensors is rendered.
    pub notes: Vec<String>,
}

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

/// Shared state while walking the tree: BSDFs are built once per XML object (a `<ref>`ed
/// BSDF used by many shapes is one BSDF), and asset file names resolve against the main
/// scene file's folder (Mitsuba resolves them there even inside `<include>`d files).
pub(crate) struct Builder {
    pub base_dir: PathBuf,
    /// `<path>` folders, searched first (Mitsuba's file resolver).
    pub search_paths: Vec<PathBuf>,
    pub bsdfs: Vec<crate::bsdf::Bsdf>,
    pub bsdf_index: HashMap<*const SceneObject, u32>,
    pub shapes: Vec<crate::shape::Shape>,
    pub emitters: Vec<Emitter>,
    pub sampling_weights: Vec<f32>,
    /// The shape whose BSDF is being built (`None` at the top level).
    pub shape: Option<ShapeContext>,
    /// Set while building when something read [`Self::shape`] (a `mesh_attribute` texture, a
    /// `bumpmap`): that BSDF is then built again for every shape instead of being shared.
    pub shape_dependent: std::cell::Cell<bool>,
    /// BSDF objects that depend on their shape (see [`Self::shape_dependent`]).
    pub shape_dependent_bsdfs: std::collections::HashSet<*const SceneObject>,
    /// `area` emitter objects built for some shape.
    pub area_emitters: std::collections::HashSet<*const SceneObject>,
}

/// What a BSDF may need to know of the shape it is built for.
pub(crate) struct ShapeContext {
    /// A triangle mesh (`obj`, `ply`, `rectangle`, `cube`), which has ∂p/∂u, ∂p/∂v and
    /// attributes in matte; the analytic shapes have neither.
    pub is_mesh: bool,
    pub attributes: Vec<std::sync::Arc<matte_scene_file::mesh::MeshAttribute>>,
    pub triangles: std::sync::Arc<Vec<[u32; 3]>>,
}

/// Where the installed package's data is (`ground_truth/<table>.json` names a packaged table),
/// as `import matte_mitsuba` registers its folder with Mitsuba's file resolver. The `matte`
/// command registers its lookup at start ([`set_package_folder`]); it is asked only for a
/// relative path found nowhere before it.
static PACKAGE_FOLDER: std::sync::OnceLock<fn() -> Option<PathBuf>> = std::sync::OnceLock::new();

/// Registers the lookup of the package folder [`Builder::resolve`] falls back on (once; later
/// calls are ignored).
pub fn set_package_folder(lookup: fn() -> Option<PathBuf>) {
    let _ = PACKAGE_FOLDER.set(lookup);
}

impl Builder {
    /// An asset path: absolute, or the first existing one relative to a `<path>` folder of the
    /// main file, the scene file's folder, matte's package folder or the working directory
    /// (Mitsuba's `FileResolver::resolve` with the resolver `load_file` sets up once
    /// `matte_mitsuba` is imported: the scene's folder prepended, `<path>` folders in front of
    /// it, the package folder registered by the import, so `ground_truth/<table>.json` names
    /// a packaged table); when none exists, the scene folder's one (for the error message).
    pub fn resolve(&self, file: &str) -> PathBuf {
        let p = Path::new(file);
        if p.is_absolute() {
            return p.to_path_buf();
        }
        let in_base = self.base_dir.join(p);
        let package = || PACKAGE_FOLDER.get().and_then(|lookup| lookup()).map(|d| d.join(p));
        self.search_paths
            .iter()
            .map(|d| d.join(p))
            .chain([in_base.clone()])
            .find(|c| c.exists())
            .or_else(|| package().filter(|c| c.exists()))
            .or_else(|| std::env::current_dir().ok().map(|d| d.join(p)).filter(|c| c.exists()))
            .unwrap_or(in_base)
    }
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
            "shape" => shape::build(&mut b, obj)?,
            // An area emitter declared at the top level is built by the shapes that `<ref>` it.
            "emitter" if obj.plugin == "area" => top_level_area.push(obj.clone()),
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

/// Error helper: `what` at the object's position.
pub(crate) fn err(obj: &SceneObject, what: impl Into<String>) -> SceneError {
    SceneError::at(&obj.pos, format!("{} \"{}\": {}", obj.tag, obj.plugin, what.into()))
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
