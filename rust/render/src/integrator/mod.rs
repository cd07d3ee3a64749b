//! Integrators: Mitsuba's `path` and `direct`, both with multiple importance sampling
//! (power heuristic) exactly where Mitsuba applies it (docs/renderer-semantics.md §7).
//!
//! Both are state machines advanced once per ray query (`start`, then `advance` with each
//! hit), so that they can be driven one path at a time ([`one_path`], the renderer's default)
//! or many paths per thread with batched ray queries ([`wavefront`]).

pub mod direct;
pub mod mis;
pub mod one_path;
pub mod path;
pub mod ptracer;
pub mod wavefront;

pub use direct::DirectIntegrator;
pub use path::PathIntegrator;
pub use ptracer::ParticleTracer;

use crate::camera::Camera;
use crate::film::ImageBlock;
use crate::geometry::Ray;
use crate::load::props::PluginProps;
use crate::sampler::{Sampler, Sampling};
use crate::scene::Scene;
use crate::shape::SurfaceInteraction;
use glam::Vec3;
use matte_scene_file::SceneError;

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

/// What every tile of one render shares: the scene, the camera, the sampler (kind, samples
/// per pixel, seed) and the film's width (the pixel index of the sampler streams).
#[derive(Clone, Copy)]
pub struct TileJob<'a> {
    pub scene: &'a Scene,
    pub camera: &'a Camera,
    pub sampling: Sampling,
    pub width: u64,
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

/// An integrator written as a state machine advanced once per ray query, which the drivers
/// ([`one_path`], [`wavefront`]) run.
pub trait SampleIntegrator {
    type State: Copy;

    /// The state for a camera ray and the first ray to trace; `None` if the radiance is zero
    /// without tracing.
    fn start(&self, camera_ray: Ray) -> Option<(Self::State, Ray)>;

    /// Consumes the pending ray's hit; pushes shadow rays onto `shadows` and returns the next
    /// ray (`None`: the sample is done).
    fn advance(
        &self,
        scene: &Scene,
        sampler: &mut Sampler,
        state: &mut Self::State,
        hit: Option<SurfaceInteraction>,
        shadows: &mut Vec<ShadowTest>,
    ) -> Option<Ray>;

    /// The radiance gathered so far.
    fn radiance(state: &mut Self::State) -> &mut Vec3;
}

/// A shadow ray an integrator asks its driver to test: if nothing blocks `ray`, the driver
/// adds `contribution` to the sample's radiance.
#[derive(Clone, Copy, Debug)]
pub struct ShadowTest {
    pub ray: Ray,
    pub contribution: Vec3,
}

/// `max_depth` (−1: unbounded, `u32::MAX`) and `rr_depth` of Mitsuba's `MonteCarloIntegrator`
/// (`src/render/integrator.cpp`), read by `path` and `ptracer`.
pub(crate) fn depths(p: &mut PluginProps) -> Result<(u32, u32), SceneError> {
    let max_depth = p.integer("max_depth", -1..=u32::MAX as i64)?;
    let rr_depth = p.integer("rr_depth", 1..=u32::MAX as i64)?;
    Ok((if max_depth < 0 { u32::MAX } else { max_depth as u32 }, rr_depth as u32))
}
