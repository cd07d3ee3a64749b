//! What the loader's files share: the [`Builder`] state while the object tree is walked (BSDFs
//! built once per XML object, the shapes and emitters so far, the shape a BSDF is built for),
//! the asset resolver (Mitsuba's `FileResolver`, with matte's package folder), the one-line
//! error helper [`err`], and the [`LoadedScene`] the walk yields.

use crate::emitter::Emitter;
use crate::film::Film;
use crate::integrator::Integrator;
use crate::sampler::Sampling;
use crate::scene::Scene;
use crate::sensor::Camera;
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

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

/// Error helper: `what` at the object's position.
pub(crate) fn err(obj: &SceneObject, what: impl Into<String>) -> SceneError {
    SceneError::at(&obj.pos, format!("{} \"{}\": {}", obj.tag, obj.plugin, what.into()))
}
