//! What the integrators and their drivers share: [`SampleIntegrator`], an integrator written as a
//! state machine advanced once per ray query, the [`ShadowTest`]s it asks its driver to trace,
//! the [`TileJob`] every tile of a render shares, and [`depths`], what Mitsuba's
//! `MonteCarloIntegrator` base reads (`path` and `ptracer`).

use crate::geometry::Ray;
use crate::load::props::PluginProps;
use crate::sampler::{Sampler, Sampling};
use crate::scene::Scene;
use crate::sensor::Camera;
use crate::shape::SurfaceInteraction;
use glam::Vec3;
use matte_scene_file::SceneError;

/// What every tile of one render shares: the scene, the camera, the sampler (kind, samples
/// per pixel, seed) and the film's width (the pixel index of the sampler streams).
#[derive(Clone, Copy)]
pub struct TileJob<'a> {
    pub scene: &'a Scene,
    pub camera: &'a Camera,
    pub sampling: Sampling,
    pub width: u64,
}

/// An integrator written as a state machine advanced once per ray query, which the drivers
/// (`one_path.rs`, `wavefront.rs`) run.
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
pub(super) fn depths(p: &mut PluginProps) -> Result<(u32, u32), SceneError> {
    let max_depth = p.integer("max_depth", -1..=u32::MAX as i64)?;
    let rr_depth = p.integer("rr_depth", 1..=u32::MAX as i64)?;
    Ok((if max_depth < 0 { u32::MAX } else { max_depth as u32 }, rr_depth as u32))
}
