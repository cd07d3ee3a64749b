//! A light sample (Mitsuba `DirectionSample3f` plus the emitter weight).

use glam::Vec3;

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
