//! Ray queries over all shapes: one compressed wide BVH (CWBVH, `obvhs`, PLOC build) whose
//! leaves are mesh triangles and whole analytic shapes. Triangles are stored in BVH leaf
//! order in the layout `obvhs` intersects fastest (v0, v0−v1, v2−v0, normal).

use crate::render::geometry::Ray;
use crate::render::shape::{Geometry, Shape};
use glam::{Vec2, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray as BvhRay, RayHit};
use std::time::Duration;

/// A closest hit: distance, shape, primitive (triangle index; 0 for analytic shapes) and
/// barycentrics (meshes only).
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub shape: u32,
    pub prim: u32,
    pub bary: Vec2,
}

/// Leaf primitive in BVH order.
#[derive(Clone, Copy, Debug)]
struct Prim {
    v0: Vec3A,
    e1: Vec3A,
    e2: Vec3A,
    ng: Vec3A,
    shape: u32,
    /// Triangle index, or `ANALYTIC`.
    index: u32,
}

const ANALYTIC: u32 = u32::MAX;

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

pub struct Accel {
    bvh: Option<CwBvh>,
    prims: Vec<Prim>,
}

impl Accel {
    pub fn build(shapes: &[Shape]) -> Self {
        let mut prims = Vec::new();
        let mut aabbs = Vec::new();
        for (si, shape) in shapes.iter().enumerate() {
            match &shape.geometry {
                Geometry::Triangles(m) => {
                    for tri in 0..m.mesh.triangles.len() as u32 {
                        let [a, b, c] = m.vertices(tri).map(Vec3A::from);
                        let (e1, e2) = (a - b, c - a);
                        prims.push(Prim { v0: a, e1, e2, ng: e1.cross(e2), shape: si as u32, index: tri });
                        aabbs.push(Aabb::from_points(&[a, b, c]));
                    }
                }
                g => {
                    let (lo, hi) = g.analytic_bounds().expect("analytic shape");
                    let z = Vec3A::ZERO;
                    prims.push(Prim { v0: z, e1: z, e2: z, ng: z, shape: si as u32, index: ANALYTIC });
                    aabbs.push(Aabb::new(lo.into(), hi.into()));
                }
            }
        }
        if prims.is_empty() {
            return Accel { bvh: None, prims };
        }
        let bvh = obvhs::cwbvh::builder::build_cwbvh(&aabbs, obvhs::BvhBuildParams::medium_build(), &mut Duration::ZERO.clone());
        let prims = bvh.primitive_indices.iter().map(|&i| prims[i as usize]).collect();
        Accel { bvh: Some(bvh), prims }
    }

    /// Closest hit along `ray` in `(0, ray.maxt)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, shapes: &[Shape]) -> Option<Hit> {
        count_ray();
        let bvh = self.bvh.as_ref()?;
        let bray = BvhRay::new(ray.o.into(), ray.d.into(), 0.0, ray.maxt);
        let mut hit = RayHit::none();
        let mut bary = Vec2::ZERO;
        let found = bvh.ray_traverse(bray, &mut hit, |r, id| {
            let p = &self.prims[id];
            if p.index == ANALYTIC {
                let local = Ray::new(ray.o, ray.d, r.tmax);
                shapes[p.shape as usize].geometry.intersect_analytic(&local).unwrap_or(f32::INFINITY)
            } else {
                match intersect_triangle(p, r) {
                    Some((t, b)) => {
                        bary = b;
                        t
                    }
                    None => f32::INFINITY,
                }
            }
        });
        if !found {
            return None;
        }
        let p = &self.prims[hit.primitive_id as usize];
        // The barycentrics belong to the last accepted candidate, which is the closest one.
        let prim = if p.index == ANALYTIC { 0 } else { p.index };
        Some(Hit { t: hit.t, shape: p.shape, prim, bary })
    }

    /// Whether anything blocks `ray` before `ray.maxt` (shadow rays).
    #[inline]
    pub fn occluded(&self, ray: &Ray, shapes: &[Shape]) -> bool {
        count_ray();
        let Some(bvh) = self.bvh.as_ref() else { return false };
        let bray = BvhRay::new(ray.o.into(), ray.d.into(), 0.0, ray.maxt);
        !bvh.ray_traverse_miss(bray, |r, id| {
            let p = &self.prims[id];
            if p.index == ANALYTIC {
                let local = Ray::new(ray.o, ray.d, r.tmax);
                shapes[p.shape as usize].geometry.intersect_analytic(&local).unwrap_or(f32::INFINITY)
            } else {
                intersect_triangle(p, r).map_or(f32::INFINITY, |(t, _)| t)
            }
        })
    }

    pub fn primitive_count(&self) -> usize {
        self.prims.len()
    }
}

/// Möller–Trumbore in the (v0, v0−v1, v2−v0) layout of madmann91's `bvh`, returning the
/// distance in `(0, tmax)` and the barycentrics `(b1, b2)` of vertices 1 and 2.
#[inline(always)]
fn intersect_triangle(p: &Prim, ray: &BvhRay) -> Option<(f32, Vec2)> {
    let c = p.v0 - ray.origin;
    let r = ray.direction.cross(c);
    let det = p.ng.dot(ray.direction);
    if det == 0.0 {
        return None;
    }
    let inv_det = 1.0 / det;
    let u = r.dot(p.e2) * inv_det;
    let v = r.dot(p.e1) * inv_det;
    let w = 1.0 - u - v;
    if u >= 0.0 && v >= 0.0 && w >= 0.0 {
        let t = p.ng.dot(c) * inv_det;
        if t > 0.0 && t < ray.tmax {
            return Some((t, Vec2::new(u, v)));
        }
    }
    None
}
