//! Uniform-by-area emitter sampling seen from a reference point: the area density `1/A`
//! becomes the solid-angle density `dist² / (|cos θ| · A)` (Mitsuba `Shape::sample_direction`
//! / `pdf_direction`), with `cos θ` taken against the normal the shape reports (the shading
//! normal for smooth meshes).

use super::interaction::DirectionSample;
use glam::{Vec2, Vec3};

/// The light sample for point `p` (normal `n`, uv `uv`) on a surface of area `area`, seen from
/// `ref_p`; `None` for a degenerate configuration.
#[inline]
pub fn direction_sample(ref_p: Vec3, p: Vec3, n: Vec3, uv: Vec2, area: f32) -> Option<DirectionSample> {
    let d = p - ref_p;
    let dist2 = d.length_squared();
    let dist = dist2.sqrt();
    if dist == 0.0 || !(area > 0.0) {
        return None;
    }
    let d = d / dist;
    Some(DirectionSample { p, n, uv, d, dist, pdf: solid_angle_pdf(dist2, d.dot(n).abs(), area) })
}

/// Density for the surface point `p` with normal `n` seen from `ref_p`.
#[inline]
pub fn pdf(ref_p: Vec3, p: Vec3, n: Vec3, area: f32) -> f32 {
    let d = p - ref_p;
    let dist2 = d.length_squared();
    solid_angle_pdf(dist2, d.dot(n).abs() / dist2.sqrt(), area)
}

#[inline]
fn solid_angle_pdf(dist2: f32, abs_cos: f32, area: f32) -> f32 {
    let pdf = dist2 / (abs_cos * area);
    if abs_cos > 0.0 && area > 0.0 && pdf.is_finite() { pdf } else { 0.0 }
}

/// Roots of `a t² + b t + c = 0` in increasing order (numerically stable form), in f64 as
/// Mitsuba's scalar variants solve their quadric intersections.
#[inline]
pub fn solve_quadratic(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 || a == 0.0 {
        return None;
    }
    let sq = disc.sqrt();
    let q = if b < 0.0 { -0.5 * (b - sq) } else { -0.5 * (b + sq) };
    let (t0, t1) = (q / a, c / q);
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}
