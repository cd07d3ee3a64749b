//! Mitsuba's `directional` emitter (`src/emitters/directional.cpp`): parallel light of
//! `irradiance` E (default 1) travelling along `direction`, or along `to_world`'s +z (not
//! both); every point receives E from the opposite direction.

use super::emitter_sample::EmitterSample;
use super::flags::EmitterFlags;
use super::light::Light;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::Shape;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Parallel light; `direction` is a unit vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Directional {
    pub direction: Vec3,
    pub irradiance: Vec3,
}

impl FromProps for Directional {
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let irradiance = p.emission("irradiance")?;
        let direction = match (p.point_opt("direction")?, p.has_property("to_world")) {
            (Some(_), true) => return Err(p.err("give either direction or to_world, not both")),
            (Some(d), false) => d,
            (None, _) => p.transform("to_world")?.transform_vector3(Vec3::Z),
        };
        let direction = direction.normalize_or_zero();
        if direction == Vec3::ZERO || !direction.is_finite() {
            return Err(p.err("direction must be a non-zero vector"));
        }
        Ok(Directional { direction, irradiance })
    }
}

impl Light for Directional {
    #[inline]
    fn flags(&self) -> EmitterFlags {
        EmitterFlags::DELTA_DIRECTION | EmitterFlags::INFINITE
    }

    #[inline]
    fn sample_direction(&self, ref_p: Vec3, _u: Vec2, _shapes: &[Shape]) -> Option<EmitterSample> {
        let d = -self.direction;
        let (dist, weight, n) = (f32::INFINITY, self.irradiance, self.direction);
        Some(EmitterSample { d, dist, pdf: 1.0, delta: true, weight, p: ref_p + d, n })
    }
}
