//! Mitsuba's sensors (`src/sensors/*.cpp`, docs/renderer-semantics.md §4), one file each:
//! `perspective`, `orthographic` and `thinlens`, with what they read alike in `projective.rs`
//! (Mitsuba's `ProjectiveCamera` and `parse_fov`, also read by the `projector` emitter).
//! [`Camera`] is any of them.

mod orthographic;
mod perspective;
mod projective;
mod thinlens;

pub use orthographic::OrthographicCamera;
pub use perspective::{PerspectiveCamera, SensorSample};
pub(crate) use projective::field_of_view;
pub use projective::{FovAxis, x_half_tan};
pub use thinlens::ThinLensCamera;

use crate::geometry::Ray;
use crate::sampler::Sampler;
use glam::Vec2;

/// The sensor: `perspective`, `orthographic` or `thinlens`.
#[derive(Clone, Debug)]
pub enum Camera {
    Perspective(PerspectiveCamera),
    Orthographic(OrthographicCamera),
    ThinLens(ThinLensCamera),
}

impl Camera {
    /// The primary ray through full-film pixel position `film_pos` (pixels, origin top-left),
    /// drawing the aperture sample from `sampler` if the sensor needs one (`thinlens`: the
    /// 2-D dimension right after the film position's, as Mitsuba's
    /// `SamplingIntegrator::render_sample` draws it).
    #[inline]
    pub fn sample_ray(&self, film_pos: Vec2, sampler: &mut Sampler) -> Ray {
        match self {
            Camera::Perspective(c) => c.ray(film_pos),
            Camera::Orthographic(c) => c.ray(film_pos),
            Camera::ThinLens(c) => c.ray(film_pos, sampler.next_2d()),
        }
    }

    /// The primary ray through `film_pos` for sensors without an aperture sample; a
    /// `thinlens` traces from its aperture's centre.
    #[inline]
    pub fn ray(&self, film_pos: Vec2) -> Ray {
        match self {
            Camera::Perspective(c) => c.ray(film_pos),
            Camera::Orthographic(c) => c.ray(film_pos),
            Camera::ThinLens(c) => c.ray(film_pos, Vec2::splat(0.5)),
        }
    }
}
