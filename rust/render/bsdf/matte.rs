//! The matte kernels (`crate::brdf`) as renderer BSDFs: `f·cos θo` from the kernel's `f`, the
//! kernel's own sampling, reflectance per RGB channel (several models are non-linear in ρ).
//! Direction convention as in the plugin: the renderer's `wi` (towards the camera side) is
//! the kernel's given direction; every model is reciprocal.

use super::BsdfSample;
use crate::brdf::{Bsdf as Model, DiffuseBrdf, dispatch};
use glam::{Vec2, Vec3};

/// `(f·cos θo, pdf)`.
#[inline]
pub fn eval_pdf(model: &Model, rho: Vec3, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return (Vec3::ZERO, 0.0);
    }
    dispatch!(model, k => {
        let f = k.eval::<3>(wi, wo, rho.to_array());
        (Vec3::from_array(f) * wo.z, k.pdf(wi, wo))
    })
}

#[inline]
pub fn sample(model: &Model, rho: Vec3, wi: Vec3, u: Vec2) -> Option<BsdfSample> {
    if wi.z <= 0.0 {
        return None;
    }
    dispatch!(model, k => {
        let s = k.sample::<3>(wi, u, rho.to_array())?;
        if !(s.pdf > 0.0) {
            return None;
        }
        Some(BsdfSample { wo: s.wo, weight: Vec3::from_array(s.weight), pdf: s.pdf, delta: false, eta: 1.0 })
    })
}
