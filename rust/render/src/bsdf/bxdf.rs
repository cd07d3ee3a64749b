//! [`Bxdf`], the method set every renderer BSDF type implements (Mitsuba's `BSDF` interface,
//! `include/mitsuba/render/bsdf.h`).

use super::flags::BsdfFlags;
use super::sample::BsdfSample;
use crate::shape::SurfaceInteraction;
use glam::{Vec2, Vec3};

/// The method set of every renderer BSDF (Mitsuba's `BSDF` interface: `eval_pdf`, `sample`,
/// `flags`), in the local shading frame (z = shading normal). `wi` points from the surface
/// towards the previous path vertex (the camera side), `wo` towards the next one.
pub trait Bxdf {
    /// `(f·|cos θo|, pdf)` of the smooth part (Dirac lobes contribute nothing here).
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32);

    /// Samples `wo` from one number for the lobe choice and two for the direction; `None`
    /// where Mitsuba's sample has zero weight or zero density.
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample>;

    /// The union of the lobes' flags, as the Mitsuba plugin sets `m_flags` (e.g.
    /// [`BsdfFlags::SMOOTH`]: light sampling is useful; [`BsdfFlags::TRANSMISSION`]).
    fn flags(&self) -> BsdfFlags;
}
