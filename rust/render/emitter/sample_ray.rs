//! Emitters as the start of light paths, for the particle tracer (`ptracer`): Mitsuba's
//! `Emitter::sample_ray` and `sample_position` (`src/emitters/{area,point,spot,projector}.cpp`,
//! v3.9.1). Weights are power / density, without the emitter-selection pmf.
//!
//! * `area` (on a triangle mesh): a uniform point (density 1/A; Mitsuba importance-samples a
//!   textured radiance by its uv instead, which has the same expectation), a cosine-weighted
//!   direction about the normal; weight `L(uv)·π·A`.
//! * `point`: a uniform direction, weight `4π·I`.
//! * `spot`: a uniform direction in the cutoff cone, weight `I·texture(uv)·falloff/pdf`.
//! * `projector`: a uniform point of the texture (Mitsuba samples it by luminance: same
//!   expectation), the direction through it; weight `E(uv)·scale·π·A_image`, with A_image
//!   the image rectangle's area at unit distance.
//!
//! docs/renderer-semantics.md §7 (ptracer).

use super::Emitter;
use crate::geometry::{Frame, warp};
use crate::shape::{Geometry, Shape};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// The first segment of a light path.
#[derive(Clone, Copy, Debug)]
pub struct LightRay {
    pub o: Vec3,
    pub d: Vec3,
    /// Surface normal at the origin (area lights: the ray is spawned off the surface), or
    /// `None` for point-like emitters.
    pub n: Option<Vec3>,
    pub weight: Vec3,
}

/// A point on an area emitter (Mitsuba `sample_position` + `sample_wavelengths`).
#[derive(Clone, Copy, Debug)]
pub struct EmitterPosition {
    pub p: Vec3,
    pub n: Vec3,
    /// Radiance at the point over its area density.
    pub weight: Vec3,
}

impl Emitter {
    /// Whether [`Self::sample_ray`] supports this emitter (the particle tracer refuses the
    /// others at load time).
    pub fn can_sample_ray(&self, shapes: &[Shape]) -> bool {
        match self {
            Emitter::Area { shape, .. } => matches!(shapes[*shape as usize].geometry, Geometry::Triangles(_)),
            Emitter::Point { .. } | Emitter::Spot { .. } | Emitter::Projector { .. } => true,
            Emitter::Directional { .. } | Emitter::Constant { .. } | Emitter::EnvMap(_) => false,
        }
    }

    /// A uniform point on an area emitter's mesh, or `None` for other emitters.
    #[inline]
    pub fn sample_position(&self, u: Vec2, shapes: &[Shape]) -> Option<EmitterPosition> {
        let Emitter::Area { shape, radiance } = self else { return None };
        let Geometry::Triangles(t) = &shapes[*shape as usize].geometry else { return None };
        let (p, n, uv) = t.sample_position(u)?;
        Some(EmitterPosition { p, n, weight: radiance.eval(uv) * t.surface_area() })
    }

    /// A light ray leaving the emitter, from two pairs of uniform numbers.
    #[inline]
    pub fn sample_ray(&self, u_pos: Vec2, u_dir: Vec2, shapes: &[Shape]) -> Option<LightRay> {
        match self {
            Emitter::Area { .. } => {
                let ep = self.sample_position(u_pos, shapes)?;
                let local = matte_brdf::sampling::square_to_cosine_hemisphere(u_dir);
                let d = Frame::from_normal(ep.n).to_world(local);
                Some(LightRay { o: ep.p, d, n: Some(ep.n), weight: ep.weight * PI })
            }
            Emitter::Point { position, intensity } => Some(LightRay {
                o: *position,
                d: warp::square_to_uniform_sphere(u_dir),
                n: None,
                weight: *intensity * (4.0 * PI),
            }),
            Emitter::Spot {
                to_world, intensity, cutoff, beam_width, cos_cutoff, cos_beam, texture, uv_factor, ..
            } => {
                let local = warp::square_to_uniform_cone(u_pos, *cos_cutoff);
                let falloff = super::spot_falloff(local.z, *cutoff, *beam_width, *cos_cutoff, *cos_beam);
                let mut weight = *intensity * (falloff / warp::uniform_cone_pdf(*cos_cutoff));
                if let Some(tex) = texture {
                    let uv = Vec2::new(local.x, local.y) / (local.z * *uv_factor) * 0.5 + 0.5;
                    weight *= tex.eval(uv);
                }
                let d = to_world.transform_vector3(local).normalize();
                Some(LightRay { o: to_world.translation.into(), d, n: None, weight })
            }
            Emitter::Projector { to_world, irradiance, tan_half, aspect, scale, .. } => {
                let uv = u_dir;
                let local = Vec3::new((1.0 - 2.0 * uv.x) * tan_half, (1.0 - 2.0 * uv.y) * tan_half / aspect, 1.0);
                let d = to_world.transform_vector3(local.normalize()).normalize();
                let image_area = 4.0 * tan_half * tan_half / aspect;
                let weight = irradiance.eval(uv) * (scale * PI * image_area);
                Some(LightRay { o: to_world.translation.into(), d, n: None, weight })
            }
            Emitter::Directional { .. } | Emitter::Constant { .. } | Emitter::EnvMap(_) => None,
        }
    }
}
