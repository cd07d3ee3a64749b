//! Mitsuba's `disk` (`src/shapes/disk.cpp`): the unit disk in z = 0 under `to_world`;
//! normal = to_world applied to +z as a normal; `flip_normals` = `to_world·S(1,1,−1)`;
//! uv = (r, φ/2π); emission sampled uniformly by area (concentric map).

use super::area_sampling;
use super::interaction::{DirectionSample, SurfaceInteraction};
use super::placement::Placement;
use crate::geometry::Ray;
use crate::load::props::PluginProps;
use glam::{Affine3A, Vec2, Vec3};
use matte_brdf::sampling::square_to_uniform_disk_concentric;
use matte_scene_file::SceneError;
use std::f32::consts::PI;

#[derive(Clone, Debug)]
pub struct Disk {
    to_world: Affine3A,
    to_object: Affine3A,
    n: Vec3,
    area: f32,
}

impl Disk {
    /// The unit disk placed by `at`: `disk` reads nothing more.
    pub(crate) fn from_props(_: &mut PluginProps, at: Placement) -> Result<Self, SceneError> {
        Ok(Disk::new(at.to_world, at.flip_normals))
    }

    pub fn new(to_world: Affine3A, flip_normals: bool) -> Self {
        let to_world = if flip_normals { to_world * Affine3A::from_scale(Vec3::new(1.0, 1.0, -1.0)) } else { to_world };
        let to_object = to_world.inverse();
        let n = (to_object.matrix3.transpose() * glam::Vec3A::Z).normalize_or_zero().into();
        let du = to_world.matrix3.x_axis;
        let dv = to_world.matrix3.y_axis;
        let area = PI * du.cross(dv).length();
        Disk { to_world, to_object, n, area }
    }

    pub fn surface_area(&self) -> f32 {
        self.area
    }

    /// Bounds of the transformed unit disk (exact for an ellipse: centre ± sqrt(u² + v²)).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let c: Vec3 = self.to_world.translation.into();
        let u: Vec3 = self.to_world.matrix3.x_axis.into();
        let v: Vec3 = self.to_world.matrix3.y_axis.into();
        let e = (u * u + v * v).map(f32::sqrt);
        (c - e, c + e)
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        let o = self.to_object.transform_point3(ray.o);
        let d = self.to_object.transform_vector3(ray.d);
        if d.z == 0.0 {
            return None;
        }
        let t = -o.z / d.z;
        if !(t > 0.0 && t < ray.maxt) {
            return None;
        }
        let x = o.x + d.x * t;
        let y = o.y + d.y * t;
        (x * x + y * y <= 1.0).then_some(t)
    }

    #[inline]
    pub fn interaction(&self, ray: &Ray, t: f32, shape: u32) -> SurfaceInteraction {
        let l = self.to_object.transform_point3(ray.at(t));
        let local = Vec2::new(l.x, l.y);
        let p = self.to_world.transform_point3(Vec3::new(local.x, local.y, 0.0));
        // Mitsuba: dp_du = to_world·(cos φ, sin φ, 0), zero at the centre.
        let radial = local.normalize_or_zero();
        let dp_du = self.to_world.transform_vector3(Vec3::new(radial.x, radial.y, 0.0));
        SurfaceInteraction::analytic(t, p, self.n, dp_du, Self::uv(local), shape, ray.d)
    }

    #[inline]
    fn uv(local: Vec2) -> Vec2 {
        let mut v = local.y.atan2(local.x) / (2.0 * PI);
        if v < 0.0 {
            v += 1.0;
        }
        Vec2::new(local.length(), v)
    }

    #[inline]
    pub fn sample_direction(&self, ref_p: Vec3, u: Vec2) -> Option<DirectionSample> {
        let local = square_to_uniform_disk_concentric(u);
        let p = self.to_world.transform_point3(Vec3::new(local.x, local.y, 0.0));
        area_sampling::direction_sample(ref_p, p, self.n, Self::uv(local), self.area)
    }

    #[inline]
    pub fn pdf_direction(&self, ref_p: Vec3, si: &SurfaceInteraction) -> f32 {
        area_sampling::pdf(ref_p, si.p, self.n, self.area)
    }
}
