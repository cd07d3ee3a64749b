//! Mitsuba's `cylinder` (`src/shapes/cylinder.cpp`): the side of the unit cylinder
//! (0,0,0)→(0,0,1), radius 1, under `to_world` (which already includes Mitsuba's
//! `T(p0)·to_frame(p1−p0)·S(r, r, |p1−p0|)`); no caps; outward normals; uv = (φ/2π, z);
//! radius = |to_world·x̂|, length = |to_world·ẑ| (a negative radius toggles `flip_normals`);
//! emission sampled uniformly by area.

use super::area_sampling;
use super::interaction::{DirectionSample, SurfaceInteraction};
use super::placement::Placement;
use crate::geometry::{Frame, Ray};
use crate::load::props::PluginProps;
use glam::{Affine3A, DVec3, Mat3, Vec2, Vec3};
use matte_scene_file::SceneError;
use std::f32::consts::PI;

#[derive(Clone, Debug)]
pub struct Cylinder {
    to_world: Affine3A,
    to_object: Affine3A,
    flip_normals: bool,
    area: f32,
}

impl Cylinder {
    /// Reads `p0` (default the origin), `p1` (default +z) and `radius` (default 1), placed by
    /// `at`: Mitsuba's `to_world · T(p0) · to_frame(p1 − p0) · S(r, r, |p1 − p0|)`.
    pub(crate) fn from_props(p: &mut PluginProps, at: Placement) -> Result<Self, SceneError> {
        let p0 = p.point_or("p0", Vec3::ZERO)?;
        let p1 = p.point_or("p1", Vec3::Z)?;
        let radius = p.float("radius")? as f32;
        let axis = p1 - p0;
        let length = axis.length();
        if !(radius.is_finite() && radius > 0.0 && length > 0.0 && length.is_finite()) {
            return Err(p.err("needs a positive radius and p0 ≠ p1"));
        }
        let f = Frame::from_normal(axis / length);
        let frame = Affine3A::from_mat3(Mat3::from_cols(f.s, f.t, f.n));
        let scale = Affine3A::from_scale(Vec3::new(radius, radius, length));
        Ok(Cylinder::new(at.to_world * Affine3A::from_translation(p0) * frame * scale, at.flip_normals))
    }

    pub fn new(to_world: Affine3A, flip_normals: bool) -> Self {
        let sx = to_world.matrix3.x_axis;
        let radius = sx.length();
        let length = to_world.matrix3.z_axis.length();
        // Mitsuba decomposes to_world and toggles the flip for a negative scale (a reflection).
        let flip = flip_normals ^ (to_world.matrix3.determinant() < 0.0);
        Cylinder { to_world, to_object: to_world.inverse(), flip_normals: flip, area: 2.0 * PI * radius * length }
    }

    pub fn surface_area(&self) -> f32 {
        self.area
    }

    /// Bounds of the transformed box [−1,1]²×[0,1] around the wall.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for i in 0..8 {
            let c =
                Vec3::new(if i & 1 == 0 { -1.0 } else { 1.0 }, if i & 2 == 0 { -1.0 } else { 1.0 }, (i >> 2) as f32);
            let p = self.to_world.transform_point3(c);
            lo = lo.min(p);
            hi = hi.max(p);
        }
        (lo, hi)
    }

    /// Nearest hit on the side wall with 0 ≤ z ≤ 1 (object space), in f64.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        let o: DVec3 = self.to_object.transform_point3(ray.o).as_dvec3();
        let d: DVec3 = self.to_object.transform_vector3(ray.d).as_dvec3();
        let a = d.x * d.x + d.y * d.y;
        let b = 2.0 * (o.x * d.x + o.y * d.y);
        let c = o.x * o.x + o.y * o.y - 1.0;
        let (t0, t1) = area_sampling::solve_quadratic(a, b, c)?;
        let maxt = ray.maxt as f64;
        for t in [t0, t1] {
            let z = o.z + d.z * t;
            if t > 0.0 && t < maxt && (0.0..=1.0).contains(&z) {
                return Some(t as f32);
            }
        }
        None
    }

    #[inline]
    pub fn interaction(&self, ray: &Ray, t: f32, shape: u32) -> SurfaceInteraction {
        let l = self.to_object.transform_point3(ray.at(t));
        let phi_dir = Vec2::new(l.x, l.y).normalize_or(Vec2::X);
        let (p, n, uv) = self.surface_point(phi_dir, l.z);
        // Mitsuba: dp_du = to_world·2π(−y, x, 0) of the local point.
        let dp_du = self.to_world.transform_vector3(Vec3::new(-l.y, l.x, 0.0));
        SurfaceInteraction::analytic(t, p, n, dp_du, uv, shape, ray.d)
    }

    /// Point, normal and uv on the wall at object-space azimuth direction `c` and height `z`.
    #[inline]
    fn surface_point(&self, c: Vec2, z: f32) -> (Vec3, Vec3, Vec2) {
        let p = self.to_world.transform_point3(Vec3::new(c.x, c.y, z));
        let n_obj = glam::Vec3A::new(c.x, c.y, 0.0);
        let mut n: Vec3 = (self.to_object.matrix3.transpose() * n_obj).normalize_or_zero().into();
        if self.flip_normals {
            n = -n;
        }
        let mut phi = c.y.atan2(c.x);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        (p, n, Vec2::new(phi / (2.0 * PI), z))
    }

    #[inline]
    pub fn sample_direction(&self, ref_p: Vec3, u: Vec2) -> Option<DirectionSample> {
        let (s, c) = (2.0 * PI * u.y).sin_cos();
        let (p, n, uv) = self.surface_point(Vec2::new(c, s), u.x);
        area_sampling::direction_sample(ref_p, p, n, uv, self.area)
    }

    #[inline]
    pub fn pdf_direction(&self, ref_p: Vec3, si: &SurfaceInteraction) -> f32 {
        area_sampling::pdf(ref_p, si.p, si.n, self.area)
    }
}
