//! Mitsuba's `direct` integrator (`src/integrators/direct.cpp`): visible emitters unweighted,
//! then `emitter_samples` light samples and `bsdf_samples` BSDF samples combined with the
//! power heuristic on the sample-count-weighted densities.
//!
//! Quirk copied on purpose (docs/renderer-semantics.md §7): a light sample from a **delta** light gets MIS
//! weight exactly 1 without the 1/Ne factor, so `emitter_samples = 4` makes point, spot and
//! directional lights 4× brighter in Mitsuba, and must here too for `validate` to agree.
//!
//! Like [`super::path`], a state machine advanced once per ray query: the camera ray's hit
//! gives every light sample's shadow ray and the first BSDF sample's probe ray, each probe's
//! hit gives the next probe.

use super::mis::power_heuristic;
use super::sample_integrator::{SampleIntegrator, ShadowTest};
use crate::bsdf::{BsdfFlags, BsdfSample, Bxdf};
use crate::emitter::Light;
use crate::geometry::{Ray, ray};
use crate::load::props::{FromProps, PluginProps};
use crate::sampler::Sampler;
use crate::scene::Scene;
use crate::shape::SurfaceInteraction;
use glam::Vec3;
use matte_scene_file::SceneError;

#[derive(Clone, Debug, PartialEq)]
pub struct DirectIntegrator {
    pub emitter_samples: u32,
    pub bsdf_samples: u32,
    pub hide_emitters: bool,
}

impl FromProps for DirectIntegrator {
    /// `shading_samples`, or `emitter_samples` and `bsdf_samples` (default `shading_samples`,
    /// 1), not both.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        const MAX: i64 = 1 << 20;
        let (ne, nb) = match p.integer_opt("shading_samples")? {
            Some(n) => {
                if p.has_property("emitter_samples") || p.has_property("bsdf_samples") {
                    return Err(p.err("shading_samples cannot be combined with emitter_samples or bsdf_samples"));
                }
                (n, n)
            }
            None => {
                let shading = p.integer("shading_samples", 0..=MAX)?;
                (p.integer_or("emitter_samples", shading, 0..=MAX)?, p.integer_or("bsdf_samples", shading, 0..=MAX)?)
            }
        };
        if ne < 0 || nb < 0 || ne + nb == 0 {
            return Err(p.err("needs at least one emitter or BSDF sample"));
        }
        let (emitter_samples, bsdf_samples) = (ne as u32, nb as u32);
        Ok(DirectIntegrator { emitter_samples, bsdf_samples, hide_emitters: p.boolean("hide_emitters")? })
    }
}

/// One camera sample between two ray queries.
#[derive(Clone, Copy, Debug)]
pub struct DirectState {
    /// Radiance gathered so far.
    pub l: Vec3,
    /// The ray whose hit [`DirectIntegrator::advance`] receives next.
    ray: Ray,
    /// The camera ray's hit, once found.
    first: Option<SurfaceInteraction>,
    /// The BSDF sample whose probe ray is pending.
    probe: Option<BsdfSample>,
    /// BSDF samples not drawn yet.
    bsdf_left: u32,
}

impl SampleIntegrator for DirectIntegrator {
    type State = DirectState;

    /// The state for a camera ray and the ray to trace first.
    #[inline]
    fn start(&self, camera_ray: Ray) -> Option<(DirectState, Ray)> {
        let state =
            DirectState { l: Vec3::ZERO, ray: camera_ray, first: None, probe: None, bsdf_left: self.bsdf_samples };
        Some((state, camera_ray))
    }

    #[inline]
    fn radiance(state: &mut DirectState) -> &mut Vec3 {
        &mut state.l
    }

    /// Consumes the hit of the pending ray (`None`: it escaped); pushes shadow rays onto
    /// `shadows` (the caller adds each unblocked one's contribution to `l` before the next
    /// call) and returns the next ray, `None` when the sample is done.
    #[inline]
    fn advance(
        &self,
        scene: &Scene,
        sampler: &mut Sampler,
        s: &mut DirectState,
        hit: Option<SurfaceInteraction>,
        shadows: &mut Vec<ShadowTest>,
    ) -> Option<Ray> {
        let Some(si) = s.first else { return self.at_camera_hit(scene, sampler, s, hit, shadows) };
        let (frac_lum, frac_bsdf) = self.sample_fractions();
        let nb = self.bsdf_samples as f32;
        // The pending probe's hit: emission found by BSDF sampling.
        let bs = s.probe.take().expect("a probe ray is pending after the camera hit");
        let wo = s.ray.d;
        let le_pdf = match hit {
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
            s.l += bs.weight * le * (power_heuristic(bs.pdf * frac_bsdf, pdf_e * frac_lum) / nb);
        }
        self.next_probe(scene, sampler, s, &si)
    }
}

impl DirectIntegrator {
    /// Ne/N and Nb/N, the weights of the light and BSDF densities in the power heuristic.
    #[inline]
    fn sample_fractions(&self) -> (f32, f32) {
        let (ne, nb) = (self.emitter_samples as f32, self.bsdf_samples as f32);
        (ne / (ne + nb), nb / (ne + nb))
    }

    #[inline]
    fn at_camera_hit(
        &self,
        scene: &Scene,
        sampler: &mut Sampler,
        s: &mut DirectState,
        hit: Option<SurfaceInteraction>,
        shadows: &mut Vec<ShadowTest>,
    ) -> Option<Ray> {
        let Some(si) = hit else {
            if let Some(env) = scene.environment
                && !self.hide_emitters
            {
                s.l += scene.emitters[env as usize].eval_environment(s.ray.d);
            }
            return None;
        };
        if let Some(em) = scene.surface_emitter(&si) {
            if self.hide_emitters {
                // A hidden emitter seen by the camera: the camera ray continues through it.
                let mut next = ray::spawn_ray(si.p, si.n, s.ray.d);
                next.maxt = s.ray.maxt - si.t;
                s.ray = next;
                return Some(next);
            }
            s.l += scene.emitters[em as usize].eval_surface(&si);
        }
        s.first = Some(si);
        let ne = self.emitter_samples as f32;
        let (frac_lum, frac_bsdf) = self.sample_fractions();
        let bsdf = scene.bsdf(&si);
        // The emitter samples are drawn whether or not the BSDF is smooth, as Mitsuba's JIT
        // variants draw them (the sample order matters with `ldsampler`; path.rs).
        let smooth = bsdf.flags().has(BsdfFlags::SMOOTH);
        for _ in 0..self.emitter_samples {
            let u = sampler.next_2d();
            if !smooth {
                continue;
            }
            let Some(es) = scene.sample_emitter_direction(&si, u) else { continue };
            let (f, pdf_b) = bsdf.eval_pdf(&si, si.wi, si.to_local(es.d));
            if f != Vec3::ZERO {
                let w = if es.delta { 1.0 } else { power_heuristic(es.pdf * frac_lum, pdf_b * frac_bsdf) / ne };
                shadows.push(ShadowTest { ray: scene.shadow_ray(&si, &es), contribution: f * es.weight * w });
            }
        }
        self.next_probe(scene, sampler, s, &si)
    }

    /// Draws BSDF samples until one gives a direction (its probe ray) or none are left.
    #[inline]
    fn next_probe(
        &self,
        scene: &Scene,
        sampler: &mut Sampler,
        s: &mut DirectState,
        si: &SurfaceInteraction,
    ) -> Option<Ray> {
        let bsdf = scene.bsdf(si);
        while s.bsdf_left > 0 {
            s.bsdf_left -= 1;
            let u_lobe = sampler.next_1d();
            let Some(bs) = bsdf.sample(si, si.wi, u_lobe, sampler.next_2d()) else { continue };
            s.ray = ray::spawn_ray(si.p, si.n, si.to_world(bs.wo));
            s.probe = Some(bs);
            return Some(s.ray);
        }
        None
    }
}
