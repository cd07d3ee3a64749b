//! Mitsuba's `direct` integrator (`src/integrators/direct.cpp`): visible emitters unweighted,
//! then `emitter_samples` light samples and `bsdf_samples` BSDF samples combined with the
//! power heuristic on the sample-count-weighted densities.
//!
//! Quirk copied on purpose (docs/renderer-semantics.md §7): a light sample from a **delta** light gets MIS
//! weight exactly 1 without the 1/Ne factor, so `emitter_samples = 4` makes point, spot and
//! directional lights 4× brighter in Mitsuba, and must here too for `validate` to agree.

use super::mis::power_heuristic;
use crate::render::geometry::{Ray, ray};
use crate::render::sampler::Sampler;
use crate::render::scene::Scene;
use glam::Vec3;

#[derive(Clone, Debug, PartialEq)]
pub struct DirectIntegrator {
    pub emitter_samples: u32,
    pub bsdf_samples: u32,
    pub hide_emitters: bool,
}

impl DirectIntegrator {
    #[inline]
    pub fn li(&self, scene: &Scene, sampler: &mut Sampler, camera_ray: Ray) -> Vec3 {
        let Some(si) = super::first_hit(scene, camera_ray, self.hide_emitters) else {
            return match scene.environment {
                Some(env) if !self.hide_emitters => scene.emitters[env as usize].eval_environment(camera_ray.d),
                _ => Vec3::ZERO,
            };
        };
        let mut l = Vec3::ZERO;
        if !self.hide_emitters
            && let Some(em) = scene.surface_emitter(&si)
        {
            l += scene.emitters[em as usize].eval_surface(&si);
        }
        let (ne, nb) = (self.emitter_samples as f32, self.bsdf_samples as f32);
        let n = ne + nb;
        let (frac_lum, frac_bsdf) = (ne / n, nb / n);
        let bsdf = scene.bsdf(&si);

        if bsdf.has_smooth() {
            for _ in 0..self.emitter_samples {
                let Some(es) = scene.sample_emitter_direction(&si, sampler.next_2d()) else { continue };
                let (f, pdf_b) = bsdf.eval_pdf(&si, si.wi, si.to_local(es.d));
                if f != Vec3::ZERO && scene.emitter_visible(&si, &es) {
                    let w = if es.delta { 1.0 } else { power_heuristic(es.pdf * frac_lum, pdf_b * frac_bsdf) / ne };
                    l += f * es.weight * w;
                }
            }
        }

        for _ in 0..self.bsdf_samples {
            let u_lobe = sampler.next_1d();
            let Some(bs) = bsdf.sample(&si, si.wi, u_lobe, sampler.next_2d()) else { continue };
            let wo = si.to_world(bs.wo);
            let le_pdf = match scene.intersect(&ray::spawn_ray(si.p, si.n, wo)) {
                Some(hit) => scene.surface_emitter(&hit).map(|em| {
                    let le = scene.emitters[em as usize].eval_surface(&hit);
                    (le, if bs.delta { 0.0 } else { scene.pdf_emitter_direction(si.p, em, Some(&hit)) })
                }),
                None => scene.environment.map(|env| {
                    let le = scene.emitters[env as usize].eval_environment(wo);
                    (le, if bs.delta { 0.0 } else { scene.pdf_environment(env, wo) })
                }),
            };
            if let Some((le, pdf_e)) = le_pdf {
                l += bs.weight * le * (power_heuristic(bs.pdf * frac_bsdf, pdf_e * frac_lum) / nb);
            }
        }
        l
    }
}
