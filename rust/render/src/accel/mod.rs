//! Ray queries over all shapes, with one of three arrangements ([`Backend`]):
//! - `embree` (the default): everything in one Embree 3 scene ([`embree`], the library
//!   loaded at run time by [`embree_api`]): meshes as Embree triangles, analytic shapes
//!   (spheres, disks, cylinders) as user geometries whose callbacks run the shapes' own exact
//!   intersection, as Mitsuba 3 arranges its scalar variants;
//! - `embree-meshes`: meshes in Embree, analytic shapes in a compressed wide BVH ([`cwbvh`],
//!   `obvhs`); a closest-hit query asks both and keeps the nearer hit, a shadow ray asks both;
//! - `cwbvh`: everything in the CWBVH (mesh triangles and analytic shapes as leaves).
//!
//! `MATTE_ACCEL` picks one; without Embree (library missing) matte says so once and uses
//! `cwbvh`, so every build of matte renders every scene. `matte bench` times all three on the
//! same rays (docs/performance.md).

pub mod cwbvh;
pub mod embree;
pub mod embree_api;
mod hit;

pub use hit::Hit;

use crate::geometry::Ray;
use crate::shape::Shape;
use cwbvh::CwBvhAccel;
use embree::EmbreeScene;

/// Which structures hold which shapes (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// Everything in Embree.
    Embree,
    /// Meshes in Embree, analytic shapes in the CWBVH.
    EmbreeMeshes,
    /// Everything in the CWBVH.
    CwBvh,
}

impl Backend {
    pub const ALL: [Backend; 3] = [Backend::Embree, Backend::EmbreeMeshes, Backend::CwBvh];

    pub fn name(self) -> &'static str {
        match self {
            Backend::Embree => "embree",
            Backend::EmbreeMeshes => "embree-meshes",
            Backend::CwBvh => "cwbvh",
        }
    }

    /// The environment's choice (`MATTE_ACCEL` = one of the names), `embree` by default.
    pub fn from_env() -> Self {
        match std::env::var("MATTE_ACCEL") {
            Err(_) => Backend::Embree,
            Ok(v) => Backend::ALL.into_iter().find(|b| b.name() == v).unwrap_or_else(|| {
                warn_once(&format!("MATTE_ACCEL={v:?} is not embree, embree-meshes or cwbvh; using embree"));
                Backend::Embree
            }),
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
    /// What Embree traces (nothing with `cwbvh`).
    embree: Option<EmbreeScene>,
    /// What Embree does not trace.
    bvh: CwBvhAccel,
    backend: Backend,
}

impl Accel {
    /// The structures for `shapes` with the environment's backend ([`Backend::from_env`]);
    /// if Embree cannot be loaded, a one-line note and the CWBVH for everything.
    pub fn build(shapes: &[Shape]) -> Self {
        match Self::build_with(shapes, Backend::from_env()) {
            Ok(a) => a,
            Err(why) => {
                warn_once(&format!("{why}; tracing meshes with the CWBVH"));
                Self::build_with(shapes, Backend::CwBvh).expect("the CWBVH always builds")
            }
        }
    }

    /// The structures for `shapes` with meshes in `backend`, or why that backend is unavailable.
    pub fn build_with(shapes: &[Shape], backend: Backend) -> Result<Self, String> {
        let embree = match backend {
            Backend::Embree => EmbreeScene::build(shapes, true)?,
            Backend::EmbreeMeshes => EmbreeScene::build(shapes, false)?,
            Backend::CwBvh => None,
        };
        // Whether Embree can be loaded at all, also for a scene that gives it nothing.
        if backend != Backend::CwBvh {
            embree_api::api()?;
        }
        let bvh = match backend {
            Backend::Embree => CwBvhAccel::build(&[], false),
            Backend::EmbreeMeshes => CwBvhAccel::build(shapes, false),
            Backend::CwBvh => CwBvhAccel::build(shapes, true),
        };
        Ok(Accel { embree, bvh, backend })
    }

    /// The arrangement in use.
    pub fn backend(&self) -> Backend {
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

    /// The closest hits of the `active` ones of eight rays (inactive lanes: `None`): one
    /// Embree packet query with `embree`, else one query per ray. Same answers as
    /// [`Self::intersect`] (`tests/render/accel_backends.rs`).
    #[inline]
    pub fn intersect8(&self, rays: &[Ray; 8], active: [bool; 8], shapes: &[Shape]) -> [Option<Hit>; 8] {
        match &self.embree {
            Some(e) if self.bvh.is_empty() => {
                active.iter().filter(|&&a| a).for_each(|_| count_ray());
                e.intersect8(rays, active)
            }
            _ => std::array::from_fn(|i| if active[i] { self.intersect(&rays[i], shapes) } else { None }),
        }
    }

    /// Whether anything blocks `ray` before `ray.maxt` (shadow rays).
    #[inline]
    pub fn occluded(&self, ray: &Ray, shapes: &[Shape]) -> bool {
        count_ray();
        self.embree.as_ref().is_some_and(|e| e.occluded(ray)) || self.bvh.occluded(ray, shapes)
    }

    /// [`Self::occluded`] for the `active` ones of eight rays (inactive lanes: `false`), one
    /// Embree packet query with `embree`.
    #[inline]
    pub fn occluded8(&self, rays: &[Ray; 8], active: [bool; 8], shapes: &[Shape]) -> [bool; 8] {
        match &self.embree {
            Some(e) if self.bvh.is_empty() => {
                active.iter().filter(|&&a| a).for_each(|_| count_ray());
                e.occluded8(rays, active)
            }
            _ => std::array::from_fn(|i| active[i] && self.occluded(&rays[i], shapes)),
        }
    }

    /// Triangles and analytic shapes in the structures.
    pub fn primitive_count(&self) -> usize {
        self.bvh.primitive_count() + self.embree.as_ref().map_or(0, EmbreeScene::primitive_count)
    }
}
