//! Traversal cost alone: ns per ray of each arrangement (`render::accel::Backend`) on the same rays.
//!
//! The rays are those of a path tracer's incoherent bounces: camera rays through uniformly
//! random film positions, then cosine-weighted bounces around the shading normal, and shadow
//! rays joining consecutive hit points ([`LoadedScene::walk_rays`]). Both sets are traced one
//! ray at a time on one thread, best of the repeats.

use matte_render::accel::{Accel, Backend};
use matte_render::geometry::Ray;
use matte_render::load::LoadedScene;
use std::hint::black_box;
use std::time::Instant;

/// One scene's traversal times per backend.
#[derive(Clone, Debug)]
pub struct TraversalTime {
    pub backend: Backend,
    /// Closest-hit queries.
    pub ns_per_ray: f64,
    /// Occlusion queries (shadow rays).
    pub ns_per_shadow_ray: f64,
    pub rays: usize,
    pub shadow_rays: usize,
    /// Closest-hit queries eight rays at a time ([`Accel::intersect8`]: Embree's
    /// `rtcIntersect8` with `embree`), the same rays in order.
    pub ns_per_ray_packet8: f64,
}

/// ns per closest-hit and per shadow ray of each backend available here, on the same rays.
/// The backends take turns within each repeat (best of the repeats each), so that a change in
/// the machine's load hits them alike.
pub fn time_traversal(loaded: &LoadedScene, paths: u32, repeats: u32) -> Vec<TraversalTime> {
    let (rays, shadow) = loaded.walk_rays(paths);
    let shapes = &loaded.scene.shapes;
    let accels: Vec<Accel> = Backend::ALL.into_iter().filter_map(|b| Accel::build_with(shapes, b).ok()).collect();
    let mut best = vec![(f64::INFINITY, f64::INFINITY, f64::INFINITY); accels.len()];
    let packets: Vec<[Ray; 8]> = rays.chunks_exact(8).map(|c| std::array::from_fn(|i| c[i])).collect();
    for _ in 0..repeats.max(1) + 1 {
        for (accel, best) in accels.iter().zip(&mut best) {
            let t0 = Instant::now();
            for r in &rays {
                black_box(accel.intersect(black_box(r), shapes));
            }
            let closest = t0.elapsed().as_secs_f64() * 1e9 / rays.len().max(1) as f64;
            let t0 = Instant::now();
            for r in &shadow {
                black_box(accel.occluded(black_box(r), shapes));
            }
            let occluded = t0.elapsed().as_secs_f64() * 1e9 / shadow.len().max(1) as f64;
            let t0 = Instant::now();
            for p in &packets {
                black_box(accel.intersect8(black_box(p), [true; 8], shapes));
            }
            let packet = t0.elapsed().as_secs_f64() * 1e9 / (8 * packets.len()).max(1) as f64;
            *best = (best.0.min(closest), best.1.min(occluded), best.2.min(packet));
        }
    }
    matte_render::accel::take_ray_count();
    accels
        .iter()
        .zip(best)
        .map(|(a, (ns_per_ray, ns_per_shadow_ray, ns_per_ray_packet8))| TraversalTime {
            backend: a.backend(),
            ns_per_ray,
            ns_per_shadow_ray,
            rays: rays.len(),
            shadow_rays: shadow.len(),
            ns_per_ray_packet8,
        })
        .collect()
}
