//! Ray queries over all shapes. Two structures, each for what it traces fastest:
//! - triangle meshes in Embree 3 ([`embree`], loaded at run time, [`embree_api`]), as
//!   Mitsuba 3 traces them;
//! - analytic shapes (spheres, disks, cylinders) in a compressed wide BVH ([`cwbvh`],
//!   `obvhs`), whose leaves call the shapes' own exact intersection.
//!
//! A closest-hit query asks both and keeps the nearer hit; a shadow ray asks Embree's
//! occlusion query and then the CWBVH. Without Embree (library missing, or `MATTE_ACCEL=cwbvh`)
//! the CWBVH holds the meshes' triangles too, so every build of matte renders every scene.

pub mod cwbvh;
pub mod embree;
pub mod embree_api;

use crate::render::geometry::Ray;
use crate::render::shape::Shape;
use cwbvh::CwBvhAccel;
use embree::EmbreeMeshes;
use glam::Vec2;

/// A closest hit: distance, shape, primitive (triangle index; 0 for analytic shapes) and
/// barycentrics (meshes only: `(b1, b2)` of vertices 1 and 2).
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub shape: u32,
    pub prim: u32,
    pub bary: Vec2,
}

/// Which structure traces the triangle meshes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshBackend {
    Embree,
    CwBvh,
}

impl MeshBackend {
    pub fn name(self) -> &'static str {
        match self {
            MeshBackend::Embree => "embree",
            MeshBackend::CwBvh => "cwbvh",
        }
    }

    /// The environment's choice (`MATTE_ACCEL` = `embree` | `cwbvh`), Embree by default.
    pub fn from_env() -> Self {
        match std::env::var("MATTE_ACCEL").as_deref() {
            Ok("cwbvh") => MeshBackend::CwBvh,
            Ok("embree") | Err(_) => MeshBackend::Embree,
            Ok(other) => {
                warn_once(&format!("MATTE_ACCEL={other:?} is neither \"embree\" nor \"cwbvh\"; using embree"));
                MeshBackend::Embree
            }
        }
    }
}

thread_local! {
    /// Rays traced by this thread since the last [`take_ray_count`] (for rays/s reports).
    static RAY_COUNT: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// Counts one traced ray (closest-hit or shadow).
#[inline]
pub fn count_ray() {
    RAY_COUNT.with(|c| c.set(c.get() + 1));
}

/// Returns and resets this thread's ray count.
pub fn take_ray_count() -> u64 {
    RAY_COUNT.with(|c| c.replace(0))
}

/// Prints `msg` as a one-line note on stderr, once per process.
fn warn_once(msg: &str) {
    static WARNED: std::sync::Once = std::sync::Once::new();
    WARNED.call_once(|| eprintln!("matte: note: {msg}"));
}

pub struct Accel {
    /// The meshes, when Embree traces them.
    embree: Option<EmbreeMeshes>,
    /// The analytic shapes, and the meshes when Embree does not trace them.
    bvh: CwBvhAccel,
    backend: MeshBackend,
}

impl Accel {
    /// The structures for `shapes` with the environment's backend ([`MeshBackend::from_env`]);
    /// if Embree cannot be loaded, a one-line note and the CWBVH for everything.
    pub fn build(shapes: &[Shape]) -> Self {
        match Self::build_with(shapes, MeshBackend::from_env()) {
            Ok(a) => a,
            Err(why) => {
                warn_once(&format!("{why}; tracing meshes with the CWBVH"));
                Self::build_with(shapes, MeshBackend::CwBvh).expect("the CWBVH always builds")
            }
        }
    }

    /// The structures for `shapes` with meshes in `backend`, or why that backend is unavailable.
    pub fn build_with(shapes: &[Shape], backend: MeshBackend) -> Result<Self, String> {
        let embree = match backend {
            MeshBackend::Embree => EmbreeMeshes::build(shapes)?,
            MeshBackend::CwBvh => None,
        };
        let bvh = CwBvhAccel::build(shapes, backend == MeshBackend::CwBvh);
        Ok(Accel { embree, bvh, backend })
    }

    /// The structure tracing the meshes.
    pub fn backend(&self) -> MeshBackend {
        self.backend
    }

    /// Closest hit along `ray` in `(0, ray.maxt)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, shapes: &[Shape]) -> Option<Hit> {
        count_ray();
        let mesh_hit = self.embree.as_ref().and_then(|e| e.intersect(ray));
        if self.bvh.is_empty() {
            return mesh_hit;
        }
        let maxt = mesh_hit.map_or(ray.maxt, |h| h.t);
        self.bvh.intersect(&Ray::new(ray.o, ray.d, maxt), shapes).or(mesh_hit)
    }

    /// Whether anything blocks `ray` before `ray.maxt` (shadow rays).
    #[inline]
    pub fn occluded(&self, ray: &Ray, shapes: &[Shape]) -> bool {
        count_ray();
        self.embree.as_ref().is_some_and(|e| e.occluded(ray)) || self.bvh.occluded(ray, shapes)
    }

    /// Triangles and analytic shapes in the structures.
    pub fn primitive_count(&self) -> usize {
        self.bvh.primitive_count() + self.embree.as_ref().map_or(0, EmbreeMeshes::triangle_count)
    }
}
