//! Sample warps (Mitsuba `include/mitsuba/core/warp.h`) used by shape and emitter sampling.
//! The cosine hemisphere and concentric disk live with the kernels (`brdf::sampling`).

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Uniform direction on the unit sphere; pdf `1/4π`.
#[inline]
pub fn square_to_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.y;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.x).sin_cos();
    Vec3::new(r * c, r * s, z)
}

pub const UNIFORM_SPHERE_PDF: f32 = 1.0 / (4.0 * PI);

/// Uniform direction in the cone of half-angle `acos(cos_max)` around +z.
#[inline]
pub fn square_to_uniform_cone(u: Vec2, cos_max: f32) -> Vec3 {
    let cos_t = (1.0 - u.x) + u.x * cos_max;
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec3::new(c * sin_t, s * sin_t, cos_t)
}

/// Density of [`square_to_uniform_cone`] (zero-width cones give infinity, which callers avoid).
#[inline]
pub fn uniform_cone_pdf(cos_max: f32) -> f32 {
    1.0 / (2.0 * PI * (1.0 - cos_max))
}

/// Uniform barycentrics `(b1, b2)` on a triangle (Mitsuba `square_to_uniform_triangle`).
#[inline]
pub fn square_to_uniform_triangle(u: Vec2) -> Vec2 {
    let t = (1.0 - u.x).max(0.0).sqrt();
    Vec2::new(1.0 - t, t * u.y)
}
