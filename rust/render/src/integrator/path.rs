//! Mitsuba's `path` integrator (`src/integrators/path.cpp`): emitter sampling and BSDF
//! sampling combined with the power heuristic; `max_depth` counts path segments (1 = visible
//! emitters only, 2 = direct lighting, −1 = unbounded); Russian roulette from `rr_depth` with
//! survival `min(max(β)·η², 0.95)`; no light sampling at purely specular surfaces.
//!
//! The integrator is a state machine ([`PathState`]) advanced once per ray query, so that
//! the one-path driver ([`super::one_path::li`]) and the renderer's many-paths-per-thread
//! driver ([`super::wavefront`]) run the same rules and draw the same numbers from each
//! pixel's sampler in the same order. That order is Mitsuba's: per vertex an emitter 2-D
//! sample, the lobe 1-D and direction 2-D samples, the roulette 1-D sample.

use super::mis::power_heuristic;
use super::sample_integrator::{SampleIntegrator, ShadowTest};
use crate::bsdf::{BsdfFlags, Bxdf};
use crate::emitter::Light;
use crate::geometry::{Ray, ray};
use crate::load::props::{FromProps, PluginProps};
use crate::sampler::Sampler;
use crate::scene::Scene;
use crate::shape::SurfaceInteraction;
use glam::Vec3;
use matte_scene_file::SceneError;

#[derive(Clone, Debug, PartialEq)]
pub struct PathIntegrator {
    /// Maximum number of path segments; `u32::MAX` for Mitsuba's −1.
    pub max_depth: u32,
    pub rr_depth: u32,
    pub hide_emitters: bool,
}

impl FromProps for PathIntegrator {
    /// Also `volpath` and `volpathmis`: on a scene without media (matte refuses media, see
    /// `load/scope.rs`) they sample the same surface paths, with the same MIS weights and
    /// Russian roulette, so their expected image is `path`'s; `use_spectral_mis` only weighs
    /// wavelengths inside media.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        if p.object().plugin == "volpathmis" {
            let _ = p.boolean("use_spectral_mis")?;
        }
        let (max_depth, rr_depth) = super::sample_integrator::depths(p)?;
        Ok(PathIntegrator { max_depth, rr_depth, hide_emitters: p.boolean("hide_emitters")? })
    }
}

/// One path between two ray queries.
#[derive(Clone, Copy, Debug)]
pub struct PathState {
    /// Radiance gathered so far.
    pub l: Vec3,
    beta: Vec3,
    eta: f32,
    /// Path segments traced before the pending ray (0: the camera ray).
    depth: u32,
    prev_p: Vec3,
    prev_pdf: f32,
    prev_delta: bool,
    /// The ray whose hit [`PathIntegrator::advance`] receives next.
    ray: Ray,
}

impl SampleIntegrator for PathIntegrator {
    type State = PathState;

    #[inline]
    fn radiance(state: &mut PathState) -> &mut Vec3 {
        &mut state.l
    }

    /// The state for a camera ray and the ray to trace first; `None` if `max_depth` = 0
    /// (the radiance is then zero).
    #[inline]
    fn start(&self, camera_ray: Ray) -> Option<(PathState, Ray)> {
        (self.max_depth > 0).then(|| {
            let state = PathState {
                l: Vec3::ZERO,
                beta: Vec3::ONE,
                eta: 1.0,
                depth: 0,
                prev_p: camera_ray.o,
                prev_pdf: 1.0,
                prev_delta: true,
                ray: camera_ray,
            };
            (state, camera_ray)
        })
    }

    /// Consumes the hit of the pending ray (`None`: it escaped): adds emission, samples the
    /// emitters (pushing the shadow ray to test onto `shadows`; the caller adds its
    /// contribution to `l` if nothing blocks it, before the next call) and the BSDF (returning
    /// the next ray, `None` when the path ends).
    #[inline]
    fn advance(
        &self,
        scene: &Scene,
        sampler: &mut Sampler,
        s: &mut PathState,
        hit: Option<SurfaceInteraction>,
        shadows: &mut Vec<ShadowTest>,
    ) -> Option<Ray> {
        let Some(si) = hit else {
            // Escaped: the environment (hidden only for the camera ray).
            if let Some(env) = scene.environment
                && !(s.depth == 0 && self.hide_emitters)
            {
                let w =
                    if s.prev_delta { 1.0 } else { power_heuristic(s.prev_pdf, scene.pdf_environment(env, s.ray.d)) };
                s.l += s.beta * scene.emitters[env as usize].eval_environment(s.ray.d) * w;
            }
            return None;
        };
        let emitter = scene.surface_emitter(&si);
        if s.depth == 0 && self.hide_emitters && emitter.is_some() {
            // A hidden emitter seen by the camera: the camera ray continues through it.
            let mut next = ray::spawn_ray(si.p, si.n, s.ray.d);
            next.maxt = s.ray.maxt - si.t;
            s.ray = next;
            return Some(next);
        }
        if let Some(em) = emitter {
            let le = scene.emitters[em as usize].eval_surface(&si);
            if le != Vec3::ZERO {
                let w = if s.prev_delta {
                    1.0
                } else {
                    power_heuristic(s.prev_pdf, scene.pdf_emitter_direction(s.prev_p, em, Some(&si)))
                };
                s.l += s.beta * le * w;
            }
        }
        if s.depth + 1 >= self.max_depth {
            return None;
        }
        let bsdf = scene.bsdf(&si);
        // Drawn at every vertex, smooth BSDF or not, as Mitsuba's JIT variants draw it (its
        // scalar ones skip it at purely specular vertices): with `ldsampler`, whose
        // dimensions are not independent, which dimension feeds which choice changes the
        // expectation (docs/renderer-semantics.md §5).
        let u_emitter = sampler.next_2d();
        if bsdf.flags().has(BsdfFlags::SMOOTH)
            && let Some(es) = scene.sample_emitter_direction(&si, u_emitter)
        {
            let (f, pdf_b) = bsdf.eval_pdf(&si, si.wi, si.to_local(es.d));
            if f != Vec3::ZERO {
                let w = if es.delta { 1.0 } else { power_heuristic(es.pdf, pdf_b) };
                shadows.push(ShadowTest { ray: scene.shadow_ray(&si, &es), contribution: s.beta * f * es.weight * w });
            }
        }
        let u_lobe = sampler.next_1d();
        let u = sampler.next_2d();
        let bs = bsdf.sample(&si, si.wi, u_lobe, u)?;
        s.beta *= bs.weight;
        s.eta *= bs.eta;
        s.prev_p = si.p;
        s.prev_pdf = bs.pdf;
        s.prev_delta = bs.delta;
        s.depth += 1;
        // Mitsuba draws the roulette number at every vertex, before and after `rr_depth`.
        let u_roulette = sampler.next_1d();
        if s.depth >= self.rr_depth {
            let q = (s.beta.max_element() * s.eta * s.eta).min(0.95);
            if !(u_roulette < q) {
                return None;
            }
            s.beta /= q;
        }
        if !(s.beta.max_element() > 0.0) {
            return None;
        }
        s.ray = ray::spawn_ray(si.p, si.n, si.to_world(bs.wo));
        Some(s.ray)
    }
}
