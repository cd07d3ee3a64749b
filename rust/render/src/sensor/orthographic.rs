//! Mitsuba's `orthographic` sensor (`src/sensors/orthographic.cpp`, with
//! `orthographic_projection` in `include/mitsuba/render/sensor.h`). In camera space the
//! film covers x ∈ [−1, 1] and y ∈ [−1/aspect, 1/aspect] (aspect = full width / height),
//! image x grows towards −x and y downwards, as for `perspective`. The ray starts on the near
//! plane z = near_clip, goes along `to_world·(0, 0, 1)` (normalised) and ends after
//! far_clip − near_clip. Unlike `perspective`, `to_world` may scale (the view's size), but must
//! be invertible.

use super::projective::clip_range;
use crate::geometry::Ray;
use crate::load::props::PluginProps;
use glam::{Affine3A, Vec2, Vec3};
use matte_scene_file::SceneError;

#[derive(Clone, Debug)]
pub struct OrthographicCamera {
    to_world: Affine3A,
    aspect: f32,
    film_size: Vec2,
    near_clip: f32,
    maxt: f32,
    d: Vec3,
}

impl OrthographicCamera {
    /// Reads `orthographic`: an invertible `to_world` and the clip range. The camera is made
    /// for the full film size by the returned function (the sensor's film is read after it).
    pub(crate) fn from_props(p: &mut PluginProps) -> Result<impl FnOnce((u32, u32)) -> Self + use<>, SceneError> {
        let to_world = p.transform("to_world")?;
        if to_world.matrix3.determinant() == 0.0 || !to_world.is_finite() {
            return Err(p.prop_err("to_world", "must be an invertible transform"));
        }
        let (near, far, _) = clip_range(p)?;
        Ok(move |film| OrthographicCamera::new(to_world, film, near, far))
    }

    /// `film` is the full film size in pixels.
    pub fn new(to_world: Affine3A, film: (u32, u32), near_clip: f32, far_clip: f32) -> Self {
        let d = to_world.transform_vector3(Vec3::Z).normalize_or_zero();
        OrthographicCamera {
            to_world,
            aspect: (film.0 as f64 / film.1 as f64) as f32,
            film_size: Vec2::new(film.0 as f32, film.1 as f32),
            near_clip,
            maxt: far_clip - near_clip,
            d,
        }
    }

    /// The primary ray through full-film pixel position `film_pos` (pixels, origin top-left).
    #[inline]
    pub fn ray(&self, film_pos: Vec2) -> Ray {
        let s = film_pos / self.film_size;
        let near_p = Vec3::new(1.0 - 2.0 * s.x, (1.0 - 2.0 * s.y) / self.aspect, self.near_clip);
        Ray::new(self.to_world.transform_point3(near_p), self.d, self.maxt)
    }
}
