//! What emitters hand the integrators: a light sample towards a point (Mitsuba's
//! `DirectionSample3f` plus the emitter weight), and for the particle tracer a point on an
//! area emitter and a ray leaving an emitter (Mitsuba's `sample_position`, `sample_ray`).

use glam::Vec3;

/// A light sample towards a reference point.
#[derive(Clone, Copy, Debug)]
pub struct EmitterSample {
    /// Unit direction from the reference point towards the emitter.
    pub d: Vec3,
    /// Distance to the sampled point (infinite for the environment and directional lights).
    pub dist: f32,
    /// Solid-angle density (1 for delta lights; the selection pmf is applied by the scene).
    pub pdf: f32,
    pub delta: bool,
    /// `Le / pdf` (delta lights: the incident radiance factor, e.g. `I/d²`).
    pub weight: Vec3,
    /// Sampled point and its normal.
    pub p: Vec3,
    pub n: Vec3,
}

/// The first segment of a light path.
#[derive(Clone, Copy, Debug)]
pub struct LightRay {
    pub o: Vec3,
    pub d: Vec3,
    /// Surface normal at the origin (area lights: the ray is spawned off the surface), or
    /// `None` for point-like emitters.
    pub n: Option<Vec3>,
    pub weight: Vec3,
}

/// A point on an area emitter (Mitsuba `sample_position` + `sample_wavelengths`).
#[derive(Clone, Copy, Debug)]
pub struct EmitterPosition {
    pub p: Vec3,
    pub n: Vec3,
    /// Radiance at the point over its area density.
    pub weight: Vec3,
}
