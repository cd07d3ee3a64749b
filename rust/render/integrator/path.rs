//! Mitsuba's `path` integrator (`src/integrators/path.cpp`): emitter sampling and BSDF
//! sampling combined with the power heuristic; `max_depth` counts path segments (1 = visible
//! emitters only, 2 = direct lighting, −1 = unbounded); Russian roulette from `rr_depth` with
//! survival `min(max(β)·η², 0.95)`; no light sampling at purely specular surfaces.

use super::mis::power_heuristic;
use crate::render::geometry::{Ray, ray};
use crate::render::sampler::Sampler;
use crate::render::scene::Scene;
use glam::Vec3;

#[derive(Clone, Debug, PartialEq)]
pub struct PathIntegrator {
    /// Maximum number of path segments; `u32::MAX` for Mitsuba's −1.
    pub max_depth: u32,
    pub rr_depth: u32,
    pub hide_emitters: bool,
}

impl PathIntegrator {
    #[inline]
    pub fn li(&self, scene: &Scene, sampler: &mut Sampler, camera_ray: Ray) -> Vec3 {
        if self.max_depth == 0 {
            return Vec3::ZERO;
        }
        let mut l = Vec3::ZERO;
        let mut beta = Vec3::ONE;
        let mut eta = 1.0f32;
        let mut depth = 0u32;
        let mut prev_p = camera_ray.o;
        let mut prev_pdf = 1.0f32;
        let mut prev_delta = true;
        let mut ray_d = camera_ray.d;
        let mut hit = super::first_hit(scene, camera_ray, self.hide_emitters);
        loop {
            let Some(si) = hit else {
                // Escaped: the environment (hidden only for the camera ray).
                if let Some(env) = scene.environment
                    && !(depth == 0 && self.hide_emitters)
                {
                    let w = if prev_delta { 1.0 } else { power_heuristic(prev_pdf, scene.pdf_environment(env, ray_d)) };
                    l += beta * scene.emitters[env as usize].eval_environment(ray_d) * w;
                }
                break;
            };
            if let Some(em) = scene.surface_emitter(&si) {
                let le = scene.emitters[em as usize].eval_surface(&si);
                if le != Vec3::ZERO {
                    let w = if prev_delta {
                        1.0
                    } else {
                        power_heuristic(prev_pdf, scene.pdf_emitter_direction(prev_p, em, Some(&si)))
                    };
                    l += beta * le * w;
                }
            }
            if depth + 1 >= self.max_depth {
                break;
            }
            let bsdf = scene.bsdf(&si);
            if bsdf.has_smooth()
                && let Some(es) = scene.sample_emitter_direction(&si, sampler.next_2d())
            {
                let (f, pdf_b) = bsdf.eval_pdf(&si, si.wi, si.to_local(es.d));
                if f != Vec3::ZERO && scene.emitter_visible(&si, &es) {
                    let w = if es.delta { 1.0 } else { power_heuristic(es.pdf, pdf_b) };
                    l += beta * f * es.weight * w;
                }
            }
            let u_lobe = sampler.next_1d();
            let u = sampler.next_2d();
            let Some(bs) = bsdf.sample(&si, si.wi, u_lobe, u) else { break };
            beta *= bs.weight;
            eta *= bs.eta;
            prev_p = si.p;
            prev_pdf = bs.pdf;
            prev_delta = bs.delta;
            depth += 1;
            if depth >= self.rr_depth {
                let q = (beta.max_element() * eta * eta).min(0.95);
                if !(sampler.next_1d() < q) {
                    break;
                }
                beta /= q;
            }
            if !(beta.max_element() > 0.0) {
                break;
            }
            let wo = si.to_world(bs.wo);
            ray_d = wo;
            hit = scene.intersect(&ray::spawn_ray(si.p, si.n, wo));
        }
        l
    }
}
