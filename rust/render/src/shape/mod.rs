//! Shapes as the renderer sees them: world-space triangle meshes (`obj`, `ply`, `serialized`,
//! `rectangle`, `cube`) and the analytic `sphere`, `disk` and `cylinder`, each with its BSDF
//! and optional area emitter (docs/renderer-semantics.md §8). Each type reads its plugin's
//! properties in its file (`from_props`, through `PluginProps`) after what Mitsuba's `Shape`
//! base class reads ([`Placement`], `placement.rs`); the loader (`rust/render/src/load/shape.rs`)
//! picks the type by plugin name and attaches the BSDF and emitter.

pub mod area_sampling;
pub mod cylinder;
pub mod disk;
pub mod interaction;
mod placement;
pub mod sphere;
pub mod triangles;

pub use cylinder::Cylinder;
pub use disk::Disk;
pub use interaction::{DirectionSample, SurfaceInteraction};
pub(crate) use placement::Placement;
pub use sphere::Sphere;
pub use triangles::Triangles;

use crate::geometry::Ray;
use glam::{Vec2, Vec3};

#[derive(Clone, Debug)]
pub enum Geometry {
    Triangles(Triangles),
    Sphere(Sphere),
    Disk(Disk),
    Cylinder(Cylinder),
}

/// One shape of the scene.
#[derive(Clone, Debug)]
pub struct Shape {
    pub geometry: Geometry,
    /// Index into the scene's BSDFs.
    pub bsdf: u32,
    /// Index into the scene's emitters, if the shape carries an `area` emitter.
    pub emitter: Option<u32>,
    /// The XML plugin name ("obj", "sphere", …), for messages.
    pub plugin: String,
}

impl Geometry {
    pub fn surface_area(&self) -> f32 {
        match self {
            Geometry::Triangles(m) => m.surface_area(),
            Geometry::Sphere(s) => s.surface_area(),
            Geometry::Disk(d) => d.surface_area(),
            Geometry::Cylinder(c) => c.surface_area(),
        }
    }

    /// The interaction for a hit found by the acceleration structure (`prim` is the triangle
    /// index for meshes, `bary` its barycentrics).
    #[inline]
    pub fn interaction(&self, ray: &Ray, t: f32, prim: u32, bary: Vec2, shape: u32) -> SurfaceInteraction {
        match self {
            Geometry::Triangles(m) => m.interaction(prim, bary, t, ray.d, shape),
            Geometry::Sphere(s) => s.interaction(ray, t, shape),
            Geometry::Disk(d) => d.interaction(ray, t, shape),
            Geometry::Cylinder(c) => c.interaction(ray, t, shape),
        }
    }

    /// A point on the surface seen from `ref_p`, with its solid-angle density.
    #[inline]
    pub fn sample_direction(&self, ref_p: Vec3, u: Vec2) -> Option<DirectionSample> {
        match self {
            Geometry::Triangles(m) => m.sample_direction(ref_p, u),
            Geometry::Sphere(s) => s.sample_direction(ref_p, u),
            Geometry::Disk(d) => d.sample_direction(ref_p, u),
            Geometry::Cylinder(c) => c.sample_direction(ref_p, u),
        }
    }

    /// Density of [`Self::sample_direction`] for the surface point `si` seen from `ref_p`.
    #[inline]
    pub fn pdf_direction(&self, ref_p: Vec3, si: &SurfaceInteraction) -> f32 {
        match self {
            Geometry::Triangles(m) => m.pdf_direction(ref_p, si),
            Geometry::Sphere(s) => s.pdf_direction(ref_p, si),
            Geometry::Disk(d) => d.pdf_direction(ref_p, si),
            Geometry::Cylinder(c) => c.pdf_direction(ref_p, si),
        }
    }
}

impl Geometry {
    /// Hit distance of an analytic shape (meshes are intersected per triangle by the BVH).
    #[inline]
    pub fn intersect_analytic(&self, ray: &Ray) -> Option<f32> {
        match self {
            Geometry::Triangles(_) => None,
            Geometry::Sphere(s) => s.intersect(ray),
            Geometry::Disk(d) => d.intersect(ray),
            Geometry::Cylinder(c) => c.intersect(ray),
        }
    }

    /// World-space bounds of an analytic shape: (min, max).
    pub fn analytic_bounds(&self) -> Option<(Vec3, Vec3)> {
        match self {
            Geometry::Triangles(_) => None,
            Geometry::Sphere(s) => Some((s.center - Vec3::splat(s.radius), s.center + Vec3::splat(s.radius))),
            Geometry::Disk(d) => Some(d.bounds()),
            Geometry::Cylinder(c) => Some(c.bounds()),
        }
    }
}
