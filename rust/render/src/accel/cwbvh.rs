//! Ray queries over shapes with one compressed wide BVH (CWBVH, `obvhs`, PLOC build) whose
//! leaves are mesh triangles and whole analytic shapes. Triangles are stored in BVH leaf
//! order in the layout `obvhs` intersects fastest (v0, v0−v1, v2−v0, normal). With Embree
//! (`super::embree`) it holds the analytic shapes only; without, everything.

use super::hit::Hit;
use crate::geometry::Ray;
use crate::shape::{Geometry, Shape};
use glam::{Vec2, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray as BvhRay, RayHit};
use std::time::Duration;

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

pub struct CwBvhAccel {
    bvh: Option<CwBvh>,
    prims: Vec<Prim>,
}

impl CwBvhAccel {
    /// The BVH over the analytic shapes of `shapes`, and over their meshes' triangles too
    /// when `with_meshes`.
    pub fn build(shapes: &[Shape], with_meshes: bool) -> Self {
        let mut prims = Vec::new();
        let mut aabbs = Vec::new();
        for (si, shape) in shapes.iter().enumerate() {
            match &shape.geometry {
                Geometry::Triangles(_) if !with_meshes => {}
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
            return CwBvhAccel { bvh: None, prims };
        }
        let bvh = obvhs::cwbvh::builder::build_cwbvh(
            &aabbs,
            obvhs::BvhBuildParams::medium_build(),
            &mut Duration::ZERO.clone(),
        );
        let prims = bvh.primitive_indices.iter().map(|&i| prims[i as usize]).collect();
        CwBvhAccel { bvh: Some(bvh), prims }
    }

    /// Closest hit along `ray` in `(0, ray.maxt)`.
    ///
    /// Candidates are tested on `ray` itself; only the box tests see the BVH ray, which
    /// starts [`BOX_ORIGIN_SHIFT`] behind. The closest candidate is tracked here, so its
    /// distance is exact and never goes through the shifted frame.
    #[inline]
    pub fn intersect(&self, ray: &Ray, shapes: &[Shape]) -> Option<Hit> {
        let bvh = self.bvh.as_ref()?;
        let mut hit = RayHit::none();
        let mut best: Option<Hit> = None;
        let mut best_t = ray.maxt;
        bvh.ray_traverse(bvh_ray(ray), &mut hit, |_, id| {
            let p = &self.prims[id];
            let found = if p.index == ANALYTIC {
                let local = Ray::new(ray.o, ray.d, best_t);
                shapes[p.shape as usize].geometry.intersect_analytic(&local).map(|t| (t, 0, Vec2::ZERO))
            } else {
                intersect_triangle(p, ray, best_t).map(|(t, b)| (t, p.index, b))
            };
            match found {
                Some((t, prim, bary)) if t < best_t => {
                    best_t = t;
                    best = Some(Hit { t, shape: p.shape, prim, bary });
                    t + BOX_ORIGIN_SHIFT
                }
                _ => f32::INFINITY,
            }
        });
        best
    }

    /// Whether anything blocks `ray` before `ray.maxt` (shadow rays).
    #[inline]
    pub fn occluded(&self, ray: &Ray, shapes: &[Shape]) -> bool {
        let Some(bvh) = self.bvh.as_ref() else { return false };
        !bvh.ray_traverse_miss(bvh_ray(ray), |_, id| {
            let p = &self.prims[id];
            let blocked = if p.index == ANALYTIC {
                shapes[p.shape as usize].geometry.intersect_analytic(ray).is_some()
            } else {
                intersect_triangle(p, ray, ray.maxt).is_some()
            };
            // Any value below the BVH ray's tmax (≥ BOX_ORIGIN_SHIFT) ends the traversal.
            if blocked { 0.0 } else { f32::INFINITY }
        })
    }

    /// Whether the BVH holds nothing (every query misses).
    pub fn is_empty(&self) -> bool {
        self.bvh.is_none()
    }

    pub fn primitive_count(&self) -> usize {
        self.prims.len()
    }
}

/// Below this |dᵢ| (and for ±0) the slab reciprocal is ±2⁴⁰ instead of 1/dᵢ: finite, so a
/// zero extent never forms inf·0 = NaN, and a power of two, so that an origin exactly on a
/// grid plane of a node (node origin + q·extent, both exact) gives exactly t = 0. A ray with
/// 0 < |dᵢ| < 2⁻⁴⁰ would need to travel 10¹² times further than it moves along axis i to
/// reach a box it starts outside of; clamping only changes boxes within 10⁻⁸ of the origin.
const MIN_DIR_COMPONENT: f32 = 1.0 / (1u64 << 40) as f32;

/// `obvhs` enters a box at `max(t_near, 1e-4)` (its `cwbvh::node::EPSILON`), so boxes that
/// end within 1e-4 of the origin were never visited, and hits that close (a shadow ray leaving
/// a surface at a contact or in a corner, Mitsuba's ray offset is ~1e-4) were lost. The BVH ray
/// therefore starts this far behind the real origin (and ends as far later); every primitive
/// is still tested on the real ray. 2e-4 leaves room for the box tests' rounding.
const BOX_ORIGIN_SHIFT: f32 = 2e-4;

/// The `obvhs` ray for `ray`, with a slab reciprocal consistent with the traversal, starting
/// [`BOX_ORIGIN_SHIFT`] behind `ray.o`.
///
/// `obvhs` picks each slab's near and far plane, and the child order, from the sign test
/// `direction < 0`, which is false for `-0.0`. Its own `Ray::new` takes the reciprocal of
/// `-0.0` as `-1/ε`, so a `-0` component swapped near and far: every box was missed and
/// rays such as `-(0, 0, -1) = (-0, -0, 1)` (the shadow ray of a directional light pointing
/// straight down) went through everything. Here `-0` becomes `+0` (IEEE: `-0 + 0 = +0`) and
/// the reciprocal's sign always agrees with `direction < 0`.
#[inline(always)]
fn bvh_ray(ray: &Ray) -> BvhRay {
    let direction = Vec3A::from(ray.d) + Vec3A::ZERO;
    let inv = |x: f32| {
        if x.abs() >= MIN_DIR_COMPONENT {
            1.0 / x
        } else if x < 0.0 {
            -1.0 / MIN_DIR_COMPONENT
        } else {
            1.0 / MIN_DIR_COMPONENT
        }
    };
    BvhRay {
        origin: Vec3A::from(ray.o) - direction * BOX_ORIGIN_SHIFT,
        direction,
        inv_direction: Vec3A::new(inv(direction.x), inv(direction.y), inv(direction.z)),
        tmin: 0.0,
        tmax: ray.maxt + BOX_ORIGIN_SHIFT,
    }
}

/// Möller–Trumbore in the (v0, v0−v1, v2−v0) layout of madmann91's `bvh`, returning the
/// distance in `(0, tmax)` and the barycentrics `(b1, b2)` of vertices 1 and 2.
#[inline(always)]
fn intersect_triangle(p: &Prim, ray: &Ray, tmax: f32) -> Option<(f32, Vec2)> {
    let (o, d) = (Vec3A::from(ray.o), Vec3A::from(ray.d));
    let c = p.v0 - o;
    let r = d.cross(c);
    let det = p.ng.dot(d);
    if det == 0.0 {
        return None;
    }
    let inv_det = 1.0 / det;
    let u = r.dot(p.e2) * inv_det;
    let v = r.dot(p.e1) * inv_det;
    let w = 1.0 - u - v;
    if u >= 0.0 && v >= 0.0 && w >= 0.0 {
        let t = p.ng.dot(c) * inv_det;
        if t > 0.0 && t < tmax {
            return Some((t, Vec2::new(u, v)));
        }
    }
    None
}
