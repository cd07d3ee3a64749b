//! Mitsuba's `sphere` (`src/shapes/sphere.cpp`): centre and radius taken from `to_world`
//! (radius = |to_world·x̂|, a negative scale toggles `flip_normals`), normal outward even
//! when hit from inside, uv = (φ/2π, θ/π) in the object frame. Emission is sampled in the
//! visible cone from outside and uniformly by area from inside, with Mitsuba's branch
//! conditions (docs/renderer-semantics.md §8: the two branches' densities do not match on the surface, and
//! copying them keeps the expected image identical).

use super::interaction::{DirectionSample, SurfaceInteraction};
use super::placement::Placement;
use crate::geometry::ray::RAY_EPSILON;
use crate::geometry::{Frame, Ray, warp};
use crate::load::props::PluginProps;
use glam::{Affine3A, DVec3, Vec2, Vec3};
use matte_scene_file::SceneError;
use std::f32::consts::PI;

#[derive(Clone, Debug)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f32,
    pub flip_normals: bool,
    /// Rotation part only (for uv), world → object.
    to_object: Affine3A,
}

impl Sphere {
    /// Reads `center` (default the origin) and `radius` (default 1, positive), placed by `at`.
    pub(crate) fn from_props(p: &mut PluginProps, at: Placement) -> Result<Self, SceneError> {
        let center = p.point("center")?;
        let radius = p.float("radius")? as f32;
        if !(radius.is_finite() && radius > 0.0) {
            return Err(p.prop_err("radius", format!("must be positive, got {radius}")));
        }
        let m = at.to_world * Affine3A::from_translation(center) * Affine3A::from_scale(Vec3::splat(radius));
        Ok(Sphere::new(m, at.flip_normals))
    }

    /// `to_world` already includes Mitsuba's `T(center)·S(radius)`.
    pub fn new(to_world: Affine3A, flip_normals: bool) -> Self {
        let center: Vec3 = to_world.translation.into();
        let sx = to_world.matrix3.x_axis;
        let radius = sx.length();
        // Mitsuba decomposes to_world and toggles the flip for a negative scale (a reflection).
        let flip = flip_normals ^ (to_world.matrix3.determinant() < 0.0);
        // Object frame with uniform scale removed, for uv (Mitsuba: to_object without scale).
        let rot = glam::Mat3A::from_cols(
            to_world.matrix3.x_axis / radius.max(f32::MIN_POSITIVE),
            to_world.matrix3.y_axis / radius.max(f32::MIN_POSITIVE),
            to_world.matrix3.z_axis / radius.max(f32::MIN_POSITIVE),
        );
        let to_object = Affine3A::from_mat3_translation(rot.into(), center).inverse();
        Sphere { center, radius, flip_normals: flip, to_object }
    }

    pub fn surface_area(&self) -> f32 {
        4.0 * PI * self.radius * self.radius
    }

    /// Nearest hit distance in `(0, maxt)`, solved in f64 like Mitsuba's scalar variant.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        let o = ray.o.as_dvec3() - self.center.as_dvec3();
        let d: DVec3 = ray.d.as_dvec3();
        let a = d.length_squared();
        let b = 2.0 * o.dot(d);
        let c = o.length_squared() - (self.radius as f64).powi(2);
        let (t0, t1) = super::area_sampling::solve_quadratic(a, b, c)?;
        let maxt = ray.maxt as f64;
        let t = if t0 > 0.0 && t0 < maxt {
            t0
        } else if t1 > 0.0 && t1 < maxt {
            t1
        } else {
            return None;
        };
        Some(t as f32)
    }

    #[inline]
    pub fn interaction(&self, ray: &Ray, t: f32, shape: u32) -> SurfaceInteraction {
        let p_raw = ray.at(t);
        let mut n = (p_raw - self.center).normalize_or_zero();
        if n == Vec3::ZERO {
            n = Vec3::Z;
        }
        // Re-project onto the surface (Mitsuba does the same to limit error).
        let p = self.center + n * self.radius;
        let uv = self.uv(p);
        if self.flip_normals {
            n = -n;
        }
        // Mitsuba: dp_du = to_world·(−y, x, 0) of the local (unit-sphere) point.
        let l = self.to_object.transform_point3(p);
        let dp_du = self.to_object.matrix3.inverse() * glam::Vec3A::new(-l.y, l.x, 0.0);
        SurfaceInteraction::analytic(t, p, n, dp_du.into(), uv, shape, ray.d)
    }

    #[inline]
    fn uv(&self, p: Vec3) -> Vec2 {
        let l = self.to_object.transform_point3(p).normalize_or_zero();
        let theta = l.z.clamp(-1.0, 1.0).acos();
        let mut phi = l.y.atan2(l.x);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        Vec2::new(phi / (2.0 * PI), theta / PI)
    }

    #[inline]
    pub fn sample_direction(&self, ref_p: Vec3, u: Vec2) -> Option<DirectionSample> {
        let dc = self.center - ref_p;
        let dc2 = dc.length_squared();
        let radius_adj = self.radius * if self.flip_normals { 1.0 + RAY_EPSILON } else { 1.0 - RAY_EPSILON };
        let (p, n_out, pdf_cone) = if dc2 > radius_adj * radius_adj {
            // Outside: uniform in the cone of directions towards the sphere (akalin.com).
            let inv_dc = dc2.sqrt().recip();
            let sin_max = self.radius * inv_dc;
            let sin_max2 = sin_max * sin_max;
            let inv_sin_max = sin_max.recip();
            let cos_max = (1.0 - sin_max2).max(0.0).sqrt();
            let sin2 = if sin_max2 > 0.00068523 {
                let c = (cos_max - 1.0).mul_add(u.x, 1.0);
                1.0 - c * c
            } else {
                sin_max2 * u.x
            };
            let cos_t = (1.0 - sin2).max(0.0).sqrt();
            let cos_a = sin2 * inv_sin_max + cos_t * (1.0 - sin2 * inv_sin_max * inv_sin_max).max(0.0).sqrt();
            let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
            let (sp, cp) = (u.y * 2.0 * PI).sin_cos();
            let frame = Frame::from_normal(-dc * inv_dc);
            let dir = frame.to_world(Vec3::new(cp * sin_a, sp * sin_a, cos_a));
            (self.center + dir * self.radius, dir, Some(warp::uniform_cone_pdf(cos_max)))
        } else {
            let dir = warp::square_to_uniform_sphere(u);
            (self.center + dir * self.radius, dir, None)
        };
        let d = p - ref_p;
        let dist2 = d.length_squared();
        let dist = dist2.sqrt();
        if dist == 0.0 {
            return None;
        }
        let d = d / dist;
        let pdf = match pdf_cone {
            Some(pdf) => pdf,
            None => dist2 / (d.dot(n_out).abs() * self.surface_area()),
        };
        let n = if self.flip_normals { -n_out } else { n_out };
        Some(DirectionSample { p, n, uv: self.uv(p), d, dist, pdf: if pdf.is_finite() { pdf } else { 0.0 } })
    }

    /// Mitsuba's `pdf_direction`: cone density when `ref_p` is outside (decided by
    /// `r/|c−p| < 1−2⁻²⁴`), area density otherwise.
    #[inline]
    pub fn pdf_direction(&self, ref_p: Vec3, si: &SurfaceInteraction) -> f32 {
        let sin_a = self.radius / (self.center - ref_p).length();
        let pdf = if sin_a < 1.0 - f32::EPSILON / 2.0 {
            let cos_a = (1.0 - sin_a * sin_a).max(0.0).sqrt();
            warp::uniform_cone_pdf(cos_a)
        } else {
            let d = si.p - ref_p;
            let dist2 = d.length_squared();
            dist2 / ((d / dist2.sqrt()).dot(si.n).abs() * self.surface_area())
        };
        if pdf.is_finite() { pdf } else { 0.0 }
    }
}
