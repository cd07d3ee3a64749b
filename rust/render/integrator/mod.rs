//! Integrators: Mitsuba's `path` and `direct`, both with multiple importance sampling
//! (power heuristic) exactly where Mitsuba applies it (docs/renderer-semantics.md §7).

pub mod direct;
pub mod mis;
pub mod path;
pub mod ptracer;

pub use direct::DirectIntegrator;
pub use path::PathIntegrator;
pub use ptracer::ParticleTracer;

use crate::render::geometry::Ray;
use crate::render::sampler::Sampler;
use crate::render::scene::Scene;
use glam::Vec3;

#[derive(Clone, Debug)]
pub enum Integrator {
    Path(PathIntegrator),
    Direct(DirectIntegrator),
    /// Mitsuba's `ptracer`: light paths splatted to the film; rendered by
    /// [`ParticleTracer::render`], not pixel by pixel.
    ParticleTracer(ParticleTracer),
}

impl Integrator {
    /// Radiance along a camera ray.
    #[inline]
    pub fn li(&self, scene: &Scene, sampler: &mut Sampler, ray: Ray) -> Vec3 {
        match self {
            Integrator::Path(p) => p.li(scene, sampler, ray),
            Integrator::Direct(d) => d.li(scene, sampler, ray),
            // The renderer sends ptracer to its own loop (renderer::render).
            Integrator::ParticleTracer(_) => Vec3::ZERO,
        }
    }
}

/// The camera ray's first hit; with `hide_emitters`, area emitters are skipped (the ray is
/// continued through them, as Mitsuba does).
#[inline]
pub(crate) fn first_hit(
    scene: &Scene,
    mut ray: Ray,
    hide_emitters: bool,
) -> Option<crate::render::shape::SurfaceInteraction> {
    loop {
        let si = scene.intersect(&ray)?;
        if !(hide_emitters && scene.surface_emitter(&si).is_some()) {
            return Some(si);
        }
        let remaining = ray.maxt - si.t;
        ray = crate::render::geometry::ray::spawn_ray(si.p, si.n, ray.d);
        ray.maxt = remaining;
    }
}
