//! Local shading frame helpers. Convention (brdf-models.md): z is the macroscopic normal,
//! `wi` points towards the light, `wo` towards the viewer, both unit vectors.

use glam::Vec3;

/// Unit direction from polar angle `theta` and azimuth `phi` (radians).
#[inline]
pub fn spherical_direction(theta: f32, phi: f32) -> Vec3 {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    Vec3::new(st * cp, st * sp, ct)
}

/// f64 version of [`spherical_direction`] for quadrature and table building.
#[inline]
pub fn spherical_direction_f64(theta: f64, phi: f64) -> glam::DVec3 {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    glam::DVec3::new(st * cp, st * sp, ct)
}

/// `s = sin θi sin θo cos Δφ = wi·wo − μi μo`: the trig-free azimuthal term of the
/// Oren–Nayar family (research page §0).
#[inline]
pub fn azimuthal_dot(wi: Vec3, wo: Vec3) -> f32 {
    wi.x * wo.x + wi.y * wo.y
}

/// `sin θ` of a unit direction, robust for directions near the pole.
#[inline]
pub fn sin_theta(w: Vec3) -> f32 {
    (w.x * w.x + w.y * w.y).sqrt()
}

/// Both directions strictly above the surface: every matte model is one-sided.
#[inline]
pub fn both_above(wi: Vec3, wo: Vec3) -> bool {
    wi.z > 0.0 && wo.z > 0.0
}
