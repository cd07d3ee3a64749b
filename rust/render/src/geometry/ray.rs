//! Rays and Mitsuba's rules for leaving a surface (`include/mitsuba/render/interaction.h`,
//! `include/mitsuba/core/math.h`): the origin moves along the **geometric** normal by
//! `(1 + max|p_i|)·RayEpsilon` towards the side of the new direction; a shadow ray stops
//! `ShadowEpsilon` (relative) short of its target.

use glam::Vec3;

/// `RayEpsilon = 1500·2⁻²⁴`.
pub const RAY_EPSILON: f32 = 1500.0 / 16_777_216.0;
/// `ShadowEpsilon = 10·RayEpsilon`.
pub const SHADOW_EPSILON: f32 = 10.0 * RAY_EPSILON;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub o: Vec3,
    /// Unit direction.
    pub d: Vec3,
    pub maxt: f32,
}

impl Ray {
    #[inline]
    pub fn new(o: Vec3, d: Vec3, maxt: f32) -> Self {
        Ray { o, d, maxt }
    }

    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.o + self.d * t
    }
}

/// The offset origin for a ray leaving the surface point `p` (geometric normal `n`) in
/// direction `d`.
#[inline]
pub fn offset_origin(p: Vec3, n: Vec3, d: Vec3) -> Vec3 {
    let mag = (1.0 + p.abs().max_element()) * RAY_EPSILON;
    let mag = if n.dot(d) >= 0.0 { mag } else { -mag };
    p + n * mag
}

/// Mitsuba `spawn_ray`: unbounded ray from an offset origin.
#[inline]
pub fn spawn_ray(p: Vec3, n: Vec3, d: Vec3) -> Ray {
    Ray::new(offset_origin(p, n, d), d, f32::INFINITY)
}

/// Mitsuba `spawn_ray_to`: a shadow ray from the surface point towards `target`, stopping
/// `ShadowEpsilon` short of it. Returns the ray (unit direction) and the distance to `target`.
#[inline]
pub fn spawn_ray_to(p: Vec3, n: Vec3, target: Vec3) -> Ray {
    let o = offset_origin(p, n, target - p);
    let d = target - o;
    let dist = d.length();
    Ray::new(o, d / dist, dist * (1.0 - SHADOW_EPSILON))
}
