//! Mitsuba's built-in `diffuse` (`src/bsdfs/diffuse.cpp`): ρ/π, one-sided (zero when either
//! direction is below the shading surface), cosine-weighted sampling with weight ρ.

use super::BsdfSample;
use crate::brdf::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// `(f·cos θo, pdf)`.
#[inline]
pub fn eval_pdf(rho: Vec3, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return (Vec3::ZERO, 0.0);
    }
    (rho * (FRAC_1_PI * wo.z), cosine_hemisphere_pdf(wo))
}

#[inline]
pub fn sample(rho: Vec3, wi: Vec3, u: Vec2) -> Option<BsdfSample> {
    if wi.z <= 0.0 {
        return None;
    }
    let wo = square_to_cosine_hemisphere(u);
    let pdf = cosine_hemisphere_pdf(wo);
    if !(pdf > 0.0) || wo.z <= 0.0 {
        return None;
    }
    Some(BsdfSample { wo, weight: rho, pdf, delta: false, eta: 1.0 })
}
