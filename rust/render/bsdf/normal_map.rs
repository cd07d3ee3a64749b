//! Mitsuba's `normalmap` (`src/bsdfs/normalmap.cpp` and `normalmap_helpers.h`, v3.9.1): a
//! wrapper that evaluates its nested BSDF in a shading frame perturbed by a normal-map texture.
//!
//! The texture's RGB at the hit's uv maps to a normal n = 2·rgb − 1 **in the shading frame**
//! (x along the shading tangent `s`, z along the shading normal). With
//! `flip_invalid_normals` (default true) n's tangential part is negated when wi lies on the
//! other side of n than of the shading normal. The perturbed frame is n̂ = normalize(n),
//! ŝ = normalize(x − n̂·n̂ₓ), t̂ = n̂ × ŝ; wi and wo are expressed in it, and the result is zero
//! when wo is on different sides of the two normals. With `use_shadowing_function` (default
//! true) values and sample weights are multiplied by Estevez et al.'s shadow-terminator
//! term 2/(1 + √(1 + α²·tan²θo)), α² = min(1, tan²θ(n̂)/8), θo measured from the
//! unperturbed normal.
//!
//! Only the local shading frame is involved, so the result depends on the shape's tangent
//! orientation exactly as in Mitsuba (`sh_frame.s` along ∂p/∂u there).

use super::Bsdf;
use super::sample::BsdfSample;
use crate::render::geometry::Frame;
use crate::render::shape::SurfaceInteraction;
use crate::render::texture::Texture;
use glam::{Vec2, Vec3};

#[derive(Clone, Debug)]
pub struct NormalMap {
    pub normals: Texture,
    pub nested: Box<Bsdf>,
    pub flip_invalid_normals: bool,
    pub use_shadowing_function: bool,
}

/// Mitsuba's `eval_shadow_terminator(perturbed_n, wo)`.
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

impl NormalMap {
    /// The perturbed frame in the coordinates of the unperturbed shading frame.
    #[inline]
    pub fn frame(&self, si: &SurfaceInteraction, wi: Vec3) -> Frame {
        let mut n = self.normals.eval(si) * 2.0 - Vec3::ONE;
        if self.flip_invalid_normals && wi.z * wi.dot(n) <= 0.0 {
            n = Vec3::new(-n.x, -n.y, n.z);
        }
        let n = n.normalize();
        let s = (Vec3::X - n * n.x).normalize();
        Frame { s, t: n.cross(s), n }
    }

    #[inline]
    pub fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        let frame = self.frame(si, wi);
        // A texel that maps to a zero or purely tangential (1, 0, 0) normal has no frame
        // (Mitsuba would produce NaN): no contribution.
        if !frame_is_finite(&frame) {
            return (Vec3::ZERO, 0.0);
        }
        let (pwi, pwo) = (frame.to_local(wi), frame.to_local(wo));
        // `> 0` is false for NaN (a degenerate normal map texel).
        if !(wo.z * pwo.z > 0.0) {
            return (Vec3::ZERO, 0.0);
        }
        let (mut f, pdf) = self.nested.eval_pdf(si, pwi, pwo);
        if self.use_shadowing_function {
            f *= shadow_terminator(frame.n, wo);
        }
        (f, pdf)
    }

    #[inline]
    pub fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let frame = self.frame(si, wi);
        if !frame_is_finite(&frame) {
            return None;
        }
        let mut s = self.nested.sample(si, frame.to_local(wi), u_lobe, u)?;
        let wo = frame.to_world(s.wo);
        if !(s.wo.z * wo.z > 0.0) || s.weight == Vec3::ZERO {
            return None;
        }
        s.wo = wo;
        if self.use_shadowing_function {
            s.weight *= shadow_terminator(frame.n, wo);
        }
        Some(s)
    }
}

#[inline]
fn frame_is_finite(f: &Frame) -> bool {
    f.s.is_finite() && f.t.is_finite() && f.n.is_finite()
}
