//! Cosine-weighted hemisphere sampling, written to reproduce Mitsuba 3.9.1's
//! `warp::square_to_cosine_hemisphere` (Shirley–Chiu concentric disk map with Dave Cline's
//! branch-reduced form, `include/mitsuba/core/warp.h`) so that `lambert` draws the same
//! directions as Mitsuba's built-in `diffuse` for the same sample inputs.

use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4};

/// Uniform disk sample from the unit square (concentric map).
#[inline]
pub fn square_to_uniform_disk_concentric(u: Vec2) -> Vec2 {
    let x = 2.0f32.mul_add(u.x, -1.0);
    let y = 2.0f32.mul_add(u.y, -1.0);
    if x == 0.0 && y == 0.0 {
        return Vec2::ZERO;
    }
    let quadrant_1_or_3 = x.abs() < y.abs();
    let (r, rp) = if quadrant_1_or_3 { (y, x) } else { (x, y) };
    let mut phi = FRAC_PI_4 * rp / r;
    if quadrant_1_or_3 {
        phi = FRAC_PI_2 - phi;
    }
    let (s, c) = phi.sin_cos();
    Vec2::new(r * c, r * s)
}

/// Cosine-weighted direction in the upper hemisphere; density [`cosine_hemisphere_pdf`].
#[inline]
pub fn square_to_cosine_hemisphere(u: Vec2) -> Vec3 {
    let p = square_to_uniform_disk_concentric(u);
    let z = (1.0 - p.length_squared()).max(0.0).sqrt();
    Vec3::new(p.x, p.y, z)
}

/// Solid-angle density of [`square_to_cosine_hemisphere`]: `max(0, cos θ)/π`.
#[inline]
pub fn cosine_hemisphere_pdf(w: Vec3) -> f32 {
    FRAC_1_PI * w.z.max(0.0)
}
