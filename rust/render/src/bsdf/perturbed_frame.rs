//! The part `normalmap` and `bumpmap` share (Mitsuba 3.9.1 `src/bsdfs/normalmap_helpers.h`):
//! the nested BSDF evaluated and sampled in a perturbed shading frame, zero when `wo` lies on
//! different sides of the perturbed and the unperturbed normal, and Estevez et al.'s
//! shadow-terminator term on values and weights when `use_shadowing_function` is set.
//! Each wrapper builds its own frame (from a normal map, from a height map's gradient).

use super::bxdf::Bxdf;
use super::sample::BsdfSample;
use crate::geometry::Frame;
use crate::shape::SurfaceInteraction;
use glam::{Vec2, Vec3};

/// Mitsuba's `eval_shadow_terminator(perturbed_n, wo)`: 2/(1 + √(1 + α²·tan²θo)) with
/// α² = min(1, tan²θ(n̂)/8), θo measured from the unperturbed normal.
#[inline]
pub fn shadow_terminator(perturbed_n: Vec3, wo: Vec3) -> f32 {
    let alpha2 = (0.125 * tan_theta_2(perturbed_n)).min(1.0);
    2.0 / (1.0 + (1.0 + alpha2 * tan_theta_2(wo)).sqrt())
}

/// Mitsuba's `Frame3f::tan_theta_2`.
#[inline]
fn tan_theta_2(v: Vec3) -> f32 {
    (1.0 - v.z * v.z).max(0.0) / (v.z * v.z)
}

/// A texel or gradient that gives no frame (zero or NaN normal): Mitsuba would produce NaN.
#[inline]
fn is_finite(f: &Frame) -> bool {
    f.s.is_finite() && f.t.is_finite() && f.n.is_finite()
}

/// `(f·|cos θo|, pdf)` of `nested` in `frame` (given in the unperturbed shading frame, like
/// `wi` and `wo`); zero without a frame.
#[inline]
pub fn eval_pdf(
    nested: &impl Bxdf,
    frame: &Frame,
    shadowing: bool,
    si: &SurfaceInteraction,
    wi: Vec3,
    wo: Vec3,
) -> (Vec3, f32) {
    if !is_finite(frame) {
        return (Vec3::ZERO, 0.0);
    }
    let (pwi, pwo) = (frame.to_local(wi), frame.to_local(wo));
    // `> 0` is false for NaN.
    if !(wo.z * pwo.z > 0.0) {
        return (Vec3::ZERO, 0.0);
    }
    let (mut f, pdf) = nested.eval_pdf(si, pwi, pwo);
    if shadowing {
        f *= shadow_terminator(frame.n, wo);
    }
    (f, pdf)
}

/// A sample of `nested` in `frame`, its direction back in the unperturbed shading frame.
#[inline]
pub fn sample(
    nested: &impl Bxdf,
    frame: &Frame,
    shadowing: bool,
    si: &SurfaceInteraction,
    wi: Vec3,
    u_lobe: f32,
    u: Vec2,
) -> Option<BsdfSample> {
    if !is_finite(frame) {
        return None;
    }
    let mut s = nested.sample(si, frame.to_local(wi), u_lobe, u)?;
    let wo = frame.to_world(s.wo);
    if !(s.wo.z * wo.z > 0.0) || s.weight == Vec3::ZERO {
        return None;
    }
    s.wo = wo;
    if shadowing {
        s.weight *= shadow_terminator(frame.n, wo);
    }
    Some(s)
}
