//! Mitsuba's `perspective` sensor (`src/sensors/perspective.cpp`, docs/renderer-semantics.md §4): x_fov from
//! `fov_axis` with the full-film aspect; image x grows towards local −x and y downwards;
//! the ray starts on the near plane. [`Camera`] is any of the sensors.

use crate::geometry::Ray;
use glam::{Affine3A, Vec2, Vec3};

/// The sensor: `perspective`, `orthographic` or `thinlens`.
#[derive(Clone, Debug)]
pub enum Camera {
    Perspective(PerspectiveCamera),
    Orthographic(super::orthographic::OrthographicCamera),
    ThinLens(super::thinlens::ThinLensCamera),
}

impl Camera {
    /// The primary ray through full-film pixel position `film_pos` (pixels, origin top-left),
    /// drawing the aperture sample from `sampler` if the sensor needs one (`thinlens`: the
    /// 2-D dimension right after the film position's, as Mitsuba's
    /// `SamplingIntegrator::render_sample` draws it).
    #[inline]
    pub fn sample_ray(&self, film_pos: Vec2, sampler: &mut crate::sampler::Sampler) -> Ray {
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
            to_local: to_world.inverse(),
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
