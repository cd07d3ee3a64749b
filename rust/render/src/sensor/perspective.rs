//! Mitsuba's `perspective` sensor (`src/sensors/perspective.cpp`, docs/renderer-semantics.md
//! §4): x_fov from `fov_axis` with the full-film aspect; image x grows towards local −x and y
//! downwards; the ray starts on the near plane. Its connection to a scene point
//! ([`PerspectiveCamera::sample_direction`]) is what the particle tracer splats with. What it
//! reads with the other sensors is in `projective.rs`.

use super::projective::{FovAxis, clip_range, field_of_view, rigid_to_world, x_half_tan};
use crate::geometry::Ray;
use crate::load::props::PluginProps;
use glam::{Affine3A, Vec2, Vec3};
use matte_scene_file::SceneError;

/// A connection from a scene point to the camera (Mitsuba's sensor `DirectionSample3f`).
#[derive(Clone, Copy, Debug)]
pub struct SensorSample {
    /// Full-film pixel position the point projects to.
    pub film_pos: Vec2,
    /// The camera's position.
    pub p: Vec3,
    /// Importance over squared distance.
    pub weight: f32,
}

#[derive(Clone, Debug)]
pub struct PerspectiveCamera {
    to_world: Affine3A,
    to_local: Affine3A,
    /// tan(x_fov / 2).
    tan_half: f32,
    aspect: f32,
    film_size: Vec2,
    principal_offset: Vec2,
    near_clip: f32,
    far_clip: f32,
}

impl PerspectiveCamera {
    /// Reads `perspective`: a rigid `to_world`, the field of view, the clip range and the
    /// principal point offsets. The camera is made for the full film size by the returned
    /// function (the sensor's film is read after the camera's properties).
    pub(crate) fn from_props(p: &mut PluginProps) -> Result<impl FnOnce((u32, u32)) -> Self + use<>, SceneError> {
        let to_world = rigid_to_world(p)?;
        let (fov_deg, axis) = field_of_view(p)?;
        let (near, far, _) = clip_range(p)?;
        let ppo = Vec2::new(
            principal_point_offset(p, "principal_point_offset_x")?,
            principal_point_offset(p, "principal_point_offset_y")?,
        );
        Ok(move |film| PerspectiveCamera::new(to_world, fov_deg, axis, film, ppo, near, far))
    }

    /// `fov_deg` along `axis`; `film` is the full film size in pixels.
    pub fn new(
        to_world: Affine3A,
        fov_deg: f64,
        axis: FovAxis,
        film: (u32, u32),
        principal_offset: Vec2,
        near_clip: f32,
        far_clip: f32,
    ) -> Self {
        let aspect = film.0 as f64 / film.1 as f64;
        let x_half = x_half_tan(fov_deg, axis, aspect);
        PerspectiveCamera {
            to_world,
            to_local: to_world.inverse(),
            tan_half: x_half as f32,
            aspect: aspect as f32,
            film_size: Vec2::new(film.0 as f32, film.1 as f32),
            principal_offset,
            near_clip,
            far_clip,
        }
    }

    /// Mitsuba's `PerspectiveCamera::sample_direction` (`src/sensors/perspective.cpp`): the
    /// connection from world point `p` to the camera, for the particle tracer. `None` outside
    /// the clip range or the film. Returns the full-film pixel position, the camera position
    /// and the importance `W(d)/dist²`, W = 1/(A·cos³θ) with A the image rectangle's area at
    /// unit distance.
    #[inline]
    pub fn sample_direction(&self, p: Vec3) -> Option<SensorSample> {
        let local = self.to_local.transform_point3(p);
        if !(local.z >= self.near_clip && local.z <= self.far_clip) {
            return None;
        }
        let s = Vec2::new(
            0.5 * (1.0 - local.x / (local.z * self.tan_half)),
            0.5 * (1.0 - local.y * self.aspect / (local.z * self.tan_half)),
        ) - self.principal_offset;
        if !(s.cmpge(Vec2::ZERO).all() && s.cmple(Vec2::ONE).all()) {
            return None;
        }
        let dist2 = local.length_squared();
        let cos = local.z / dist2.sqrt();
        let area = 4.0 * self.tan_half * self.tan_half / self.aspect;
        let importance = 1.0 / (area * cos * cos * cos);
        Some(SensorSample {
            film_pos: s * self.film_size,
            p: self.to_world.transform_point3(Vec3::ZERO),
            weight: importance / dist2,
        })
    }

    /// The primary ray through full-film pixel position `film_pos` (pixels, origin top-left).
    #[inline]
    pub fn ray(&self, film_pos: Vec2) -> Ray {
        let s = film_pos / self.film_size + self.principal_offset;
        let local = Vec3::new((1.0 - 2.0 * s.x) * self.tan_half, (1.0 - 2.0 * s.y) * self.tan_half / self.aspect, 1.0);
        let dl = local.normalize();
        let d = self.to_world.transform_vector3(dl).normalize();
        let inv_z = 1.0 / dl.z;
        let o = self.to_world.transform_point3(Vec3::ZERO) + d * (self.near_clip * inv_z);
        Ray::new(o, d, (self.far_clip - self.near_clip) * inv_z)
    }
}

/// A principal point offset (a fraction of the film size). Mitsuba takes any float; a NaN or
/// one so large that the ray direction overflows f32 would give NaN camera rays, so matte
/// requires a finite value within ±10⁶ film sizes.
fn principal_point_offset(p: &mut PluginProps, name: &str) -> Result<f32, SceneError> {
    let v = p.float(name)?;
    if v.is_nan() || v.abs() > 1e6 {
        return Err(p.prop_err(name, format!("must be a finite fraction of the film size within ±1e6, got {v}")));
    }
    Ok(v as f32)
}
