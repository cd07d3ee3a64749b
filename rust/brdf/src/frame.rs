//! Directions from angles (the CLI's and the tests' inputs). Convention
//! (`docs/conventions.md#local-frame`): z is the macroscopic normal, `wi` points towards the
//! light, `wo` towards the viewer, both unit vectors.

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
