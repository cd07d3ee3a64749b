//! Mitsuba's `point` emitter (`src/emitters/point.cpp`): an isotropic point light of
//! `intensity` I (default 1) at `position` or at `to_world`'s origin (not both): radiance
//! `I / d²` towards a point at distance d; for the particle tracer a uniform direction, weight
//! `4π·I`.

use super::emitter_sample::{EmitterSample, LightRay};
use super::flags::EmitterFlags;
use super::light::Light;
use crate::geometry::warp;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::Shape;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;
use std::f32::consts::PI;

/// Isotropic point light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    pub position: Vec3,
    pub intensity: Vec3,
}

impl FromProps for Point {
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let intensity = p.emission("intensity")?;
        let position = match (p.point_opt("position")?, p.has_property("to_world")) {
            (Some(_), true) => return Err(p.err("give either position or to_world, not both")),
            (Some(position), false) => position,
            (None, _) => p.transform("to_world")?.translation.into(),
        };
        Ok(Point { position, intensity })
    }
}

impl Light for Point {
    #[inline]
    fn flags(&self) -> EmitterFlags {
        EmitterFlags::DELTA_POSITION
    }

    #[inline]
    fn sample_direction(&self, ref_p: Vec3, _u: Vec2, _shapes: &[Shape]) -> Option<EmitterSample> {
        let d = self.position - ref_p;
        let dist2 = d.length_squared();
        let dist = dist2.sqrt();
        if dist == 0.0 {
            return None;
        }
        let d = d / dist;
        let weight = self.intensity / dist2;
        Some(EmitterSample { d, dist, pdf: 1.0, delta: true, weight, p: self.position, n: -d })
    }

    #[inline]
    fn can_sample_ray(&self, _shapes: &[Shape]) -> bool {
        true
    }

    #[inline]
    fn sample_ray(&self, _u_pos: Vec2, u_dir: Vec2, _shapes: &[Shape]) -> Option<LightRay> {
        let d = warp::square_to_uniform_sphere(u_dir);
        Some(LightRay { o: self.position, d, n: None, weight: self.intensity * (4.0 * PI) })
    }
}
