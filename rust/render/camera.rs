//! Mitsuba's `perspective` sensor (`src/sensors/perspective.cpp`, docs/renderer-semantics.md §4): x_fov from
//! `fov_axis` with the full-film aspect; image x grows towards local −x and y downwards;
//! the ray starts on the near plane.

use crate::render::geometry::Ray;
use glam::{Affine3A, Vec2, Vec3};

/// The sensor: `perspective` or `orthographic`.
#[derive(Clone, Debug)]
pub enum Camera {
    Perspective(PerspectiveCamera),
    Orthographic(super::orthographic::OrthographicCamera),
}

impl Camera {
    /// The primary ray through full-film pixel position `film_pos` (pixels, origin top-left).
    #[inline]
    pub fn ray(&self, film_pos: Vec2) -> Ray {
        match self {
            Camera::Perspective(c) => c.ray(film_pos),
            Camera::Orthographic(c) => c.ray(film_pos),
        }
    }
}

#[derive(Clone, Debug)]
pub struct PerspectiveCamera {
    to_world: Affine3A,
    /// tan(x_fov / 2).
    tan_half: f32,
    aspect: f32,
    film_size: Vec2,
    principal_offset: Vec2,
    near_clip: f32,
    far_clip: f32,
}

/// Which axis `fov` refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FovAxis {
    X,
    Y,
    Diagonal,
    Smaller,
    Larger,
}

/// tan(x_fov / 2) for `fov_deg` along `axis` on an image of aspect width/height (Mitsuba
/// `parse_fov`, `src/render/sensor.cpp`).
pub fn x_half_tan(fov_deg: f64, axis: FovAxis, aspect: f64) -> f64 {
    let half = (fov_deg.to_radians() * 0.5).tan();
    match axis {
        FovAxis::X => half,
        FovAxis::Y => half * aspect,
        FovAxis::Diagonal => half / (1.0 + 1.0 / (aspect * aspect)).sqrt(),
        FovAxis::Smaller => {
            if aspect > 1.0 {
                half * aspect
            } else {
                half
            }
        }
        FovAxis::Larger => {
            if aspect > 1.0 {
                half
            } else {
                half * aspect
            }
        }
    }
}

impl PerspectiveCamera {
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
            tan_half: x_half as f32,
            aspect: aspect as f32,
            film_size: Vec2::new(film.0 as f32, film.1 as f32),
            principal_offset,
            near_clip,
            far_clip,
        }
    }

    /// The x fov in degrees for a `focal_length` in mm (on the 36×24 frame, diagonal).
    pub fn focal_length_to_diagonal_fov(mm: f64) -> f64 {
        2.0 * ((36.0f64 * 36.0 + 24.0 * 24.0).sqrt() / (2.0 * mm)).atan().to_degrees()
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
