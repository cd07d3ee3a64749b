//! Rays of a path tracer's incoherent bounces in a loaded scene, for comparing and timing the
//! ray-query arrangements (`accel::Backend`): camera rays through uniformly random film
//! positions, then up to [`WALK_BOUNCES`] cosine-weighted bounces around the shading normal;
//! the shadow rays join consecutive hit points of different paths (so about half are blocked).

use super::builder::LoadedScene;
use crate::geometry::{Ray, ray};
use crate::sampler::Sampler;
use glam::{Vec2, Vec3};

/// Bounces after the camera ray.
pub const WALK_BOUNCES: u32 = 3;

impl LoadedScene {
    /// The closest-hit and shadow rays of `paths` random walks (seeded, reproducible).
    #[must_use]
    pub fn walk_rays(&self, paths: u32) -> (Vec<Ray>, Vec<Ray>) {
        let scene = &self.scene;
        let size = Vec2::new(self.film.width() as f32, self.film.height() as f32);
        let mut rays = Vec::new();
        let mut vertices: Vec<(Vec3, Vec3)> = Vec::new();
        for i in 0..paths {
            let mut s = Sampler::for_pixel(0x7261_7973, i as u64);
            let pos = s.next_2d() * size;
            let mut r = self.camera.ray(pos);
            for _ in 0..=WALK_BOUNCES {
                rays.push(r);
                let Some(si) = scene.intersect(&r) else { break };
                vertices.push((si.p, si.n));
                let u = s.next_2d();
                let (rad, phi) = (u.x.sqrt(), std::f32::consts::TAU * u.y);
                let local = Vec3::new(rad * phi.cos(), rad * phi.sin(), (1.0 - u.x).max(0.0).sqrt());
                // The side the ray came from, so that walks continue inside closed rooms.
                let local = if si.wi.z < 0.0 { -local } else { local };
                r = ray::spawn_ray(si.p, si.n, si.to_world(local));
            }
        }
        let shadow = vertices
            .windows(2)
            .filter(|w| w[0].0 != w[1].0)
            .map(|w| ray::spawn_ray_to(w[0].0, w[0].1, w[1].0))
            .filter(|r| r.maxt > 0.0)
            .collect();
        (rays, shadow)
    }
}
