//! Integrators: Mitsuba's `path` and `direct`, both with multiple importance sampling
//! (power heuristic) exactly where Mitsuba applies it (docs/renderer-semantics.md §7).
//!
//! Both are state machines advanced once per ray query (`start`, then `advance` with each
//! hit), so that they can be driven one path at a time ([`one_path`], the renderer's default)
//! or many paths per thread with batched ray queries ([`wavefront`]); what integrators and
//! drivers share is in `sample_integrator.rs`.

pub mod direct;
pub mod mis;
pub mod one_path;
pub mod path;
pub mod ptracer;
mod sample_integrator;
pub mod wavefront;

pub use direct::DirectIntegrator;
pub use path::PathIntegrator;
pub use ptracer::ParticleTracer;
pub use sample_integrator::{SampleIntegrator, ShadowTest, TileJob};

use crate::film::ImageBlock;
use crate::geometry::Ray;
use crate::sampler::Sampler;
use crate::scene::Scene;
use glam::Vec3;

/// How the renderer runs an integrator over a tile. Both give the same estimator
/// (`tests/render/render_drivers.rs`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Driver {
    /// One path at a time ([`one_path`]). The default: with scalar shading the wavefront is
    /// not faster yet (docs/performance.md).
    #[default]
    OnePath,
    /// Many paths in flight per thread with batched ray queries ([`wavefront`]), the structure
    /// for 8-wide shading.
    Wavefront,
    /// [`Driver::Wavefront`] counting each stage's time ([`wavefront::StageTicks`]), for
    /// `matte bench`'s profile split (the count costs a few percent).
    WavefrontProfiled,
}

impl Driver {
    pub fn name(self) -> &'static str {
        match self {
            Driver::Wavefront => "wavefront",
            Driver::OnePath => "one path",
            Driver::WavefrontProfiled => "wavefront, profiled",
        }
    }

    /// `matte render --driver`: `one-path` or `wavefront`.
    pub fn parse(name: &str) -> Result<Driver, String> {
        match name {
            "one-path" => Ok(Driver::OnePath),
            "wavefront" => Ok(Driver::Wavefront),
            other => Err(format!("unknown driver {other:?} (expected one-path or wavefront)")),
        }
    }
}

#[derive(Clone, Debug)]
pub enum Integrator {
    Path(PathIntegrator),
    Direct(DirectIntegrator),
    /// Mitsuba's `ptracer`: light paths splatted to the film; rendered by
    /// [`ParticleTracer::render`], not pixel by pixel.
    ParticleTracer(ParticleTracer),
}

impl From<PathIntegrator> for Integrator {
    fn from(i: PathIntegrator) -> Self {
        Integrator::Path(i)
    }
}

impl From<DirectIntegrator> for Integrator {
    fn from(i: DirectIntegrator) -> Self {
        Integrator::Direct(i)
    }
}

impl From<ParticleTracer> for Integrator {
    fn from(i: ParticleTracer) -> Self {
        Integrator::ParticleTracer(i)
    }
}

impl Integrator {
    /// Radiance along a camera ray.
    #[inline]
    pub fn li(&self, scene: &Scene, sampler: &mut Sampler, ray: Ray) -> Vec3 {
        match self {
            Integrator::Path(p) => one_path::li(p, scene, sampler, ray),
            Integrator::Direct(d) => one_path::li(d, scene, sampler, ray),
            // The renderer sends ptracer to its own loop (renderer::render).
            Integrator::ParticleTracer(_) => Vec3::ZERO,
        }
    }

    /// Renders every pixel of `block`'s tile with `driver` (the same numbers per sample with
    /// any); returns how many samples were not finite (splatted as zero).
    /// [`Driver::WavefrontProfiled`] adds to `profile`. `ptracer` renders in its own loop and
    /// gets nothing here.
    pub fn render_tile(
        &self,
        driver: Driver,
        job: &TileJob,
        block: &mut ImageBlock,
        profile: &mut wavefront::StageTicks,
    ) -> u64 {
        match self {
            Integrator::Path(p) => drive(p, driver, job, block, profile),
            Integrator::Direct(d) => drive(d, driver, job, block, profile),
            Integrator::ParticleTracer(_) => 0,
        }
    }
}

/// Runs `integrator` over `block`'s tile with `driver`.
fn drive<I: SampleIntegrator>(
    integrator: &I,
    driver: Driver,
    job: &TileJob,
    block: &mut ImageBlock,
    profile: &mut wavefront::StageTicks,
) -> u64 {
    match driver {
        Driver::OnePath => one_path::render_tile(integrator, job, block),
        Driver::Wavefront => wavefront::render_tile::<I, false>(integrator, job, block, profile),
        Driver::WavefrontProfiled => wavefront::render_tile::<I, true>(integrator, job, block, profile),
    }
}
