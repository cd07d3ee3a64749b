//! [`Light`], the method set every emitter type implements (Mitsuba's `Emitter` interface,
//! `include/mitsuba/render/emitter.h`), with the defaults of an emitter that has no use for a
//! method.

use super::emitter_sample::{EmitterPosition, EmitterSample, LightRay};
use super::flags::EmitterFlags;
use crate::shape::{Shape, SurfaceInteraction};
use glam::{Vec2, Vec3};

/// The method set of every emitter (Mitsuba's `Emitter`: `sample_direction`, `pdf_direction`,
/// `eval`, `sample_ray`, `sample_position`, `flags`). `shapes` are the scene's (an area light
/// samples its shape). Methods an emitter has no use for keep the default: nothing emitted,
/// density 0.
pub trait Light {
    /// What kind of emitter this is, as the plugin's constructor sets `m_flags`.
    fn flags(&self) -> EmitterFlags;

    /// Light sample towards the emitter from `ref_p` (the emitter-selection pmf not
    /// included). `None` when nothing can be emitted towards `ref_p`.
    fn sample_direction(&self, ref_p: Vec3, u: Vec2, shapes: &[Shape]) -> Option<EmitterSample>;

    /// Solid-angle density of [`Self::sample_direction`] for an area-light hit `si` seen
    /// from `ref_p`, or for the environment (`si = None`). Zero for delta emitters.
    #[inline]
    fn pdf_direction(&self, _ref_p: Vec3, _si: Option<&SurfaceInteraction>, _shapes: &[Shape]) -> f32 {
        0.0
    }

    /// Radiance seen at a surface hit of this (area) emitter's shape.
    #[inline]
    fn eval_surface(&self, _si: &SurfaceInteraction) -> Vec3 {
        Vec3::ZERO
    }

    /// Radiance of the environment for a ray escaping along `d`.
    #[inline]
    fn eval_environment(&self, _d: Vec3) -> Vec3 {
        Vec3::ZERO
    }

    /// Solid-angle density with which light sampling picks the environment direction `d`.
    #[inline]
    fn pdf_environment(&self, _d: Vec3) -> f32 {
        0.0
    }

    /// Whether [`Self::sample_ray`] supports this emitter (the particle tracer refuses the
    /// others at load time).
    #[inline]
    fn can_sample_ray(&self, _shapes: &[Shape]) -> bool {
        false
    }

    /// A point on an area emitter's mesh (Mitsuba `sample_position` + `sample_wavelengths`),
    /// or `None` for other emitters.
    #[inline]
    fn sample_position(&self, _u: Vec2, _shapes: &[Shape]) -> Option<EmitterPosition> {
        None
    }

    /// A light ray leaving the emitter, from two pairs of uniform numbers (the first segment
    /// of a particle tracer's path; weight = power / density, without the selection pmf).
    #[inline]
    fn sample_ray(&self, _u_pos: Vec2, _u_dir: Vec2, _shapes: &[Shape]) -> Option<LightRay> {
        None
    }
}
