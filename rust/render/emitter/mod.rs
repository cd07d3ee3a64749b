//! Emitters (Mitsuba `src/emitters/*.cpp`, docs/renderer-semantics.md §9): `area` (one-sided w.r.t. the
//! shading normal, attached to a shape), `point`, `spot`, `projector`, `directional`, and the
//! `constant` and `envmap` environments. Radiance values are linear RGB.

pub mod emitter_sample;
pub mod envmap;
pub mod sample_ray;

pub use emitter_sample::EmitterSample;
pub use envmap::EnvMap;

use crate::geometry::warp;
use crate::shape::{Shape, SurfaceInteraction};
use crate::texture::Texture;
use glam::{Affine3A, Vec2, Vec3};
use std::f32::consts::PI;

#[derive(Clone, Debug)]
pub enum Emitter {
    /// Emits `radiance` from the side its shape's shading normal points to.
    /// `radiance`: a colour or a uv texture (not a mesh attribute).
    Area { shape: u32, radiance: Texture },
    /// Isotropic point light: `intensity / d²`.
    Point { position: Vec3, intensity: Vec3 },
    /// Spot light along local +z of `to_world`; falloff linear in the angle between
    /// `beam_width` and `cutoff_angle` (radians). An optional `texture` multiplies the
    /// intensity, looked up at uv = 1/2 + 1/2·(x, y)/(z·tan cutoff) of the local direction
    /// (`src/emitters/spot.cpp`, `direction_to_uv`).
    Spot {
        to_world: Affine3A,
        to_local: Affine3A,
        intensity: Vec3,
        cutoff: f32,
        beam_width: f32,
        cos_cutoff: f32,
        cos_beam: f32,
        texture: Option<Texture>,
        uv_factor: f32,
    },
    /// Parallel light travelling along `direction` (unit) with irradiance `irradiance`.
    Directional { direction: Vec3, irradiance: Vec3 },
    /// Uniform environment of radiance `radiance`, sampled uniformly over the sphere.
    Constant { radiance: Vec3 },
    /// `projector` (`src/emitters/projector.cpp`): a pinhole at `to_world`'s origin casting
    /// the `irradiance` texture along local +z; x half-angle tangent `tan_half` over an image
    /// of aspect `aspect` (the texture's; 1 for a constant). Irradiance at local depth 1 on a
    /// plane facing it is π·scale·texture.
    Projector { to_world: Affine3A, to_local: Affine3A, irradiance: Texture, tan_half: f32, aspect: f32, scale: f32 },
    /// Image-based environment (`envmap`), importance sampled.
    EnvMap(std::sync::Arc<EnvMap>),
}

impl Emitter {
    /// Point, spot and directional lights: reachable only by light sampling.
    #[inline]
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Emitter::Point { .. } | Emitter::Spot { .. } | Emitter::Directional { .. } | Emitter::Projector { .. }
        )
    }

    /// Light sample towards the emitter from `ref_p` (the emitter-selection pmf not
    /// included). `None` when nothing can be emitted towards `ref_p`.
    #[inline]
    pub fn sample_direction(&self, ref_p: Vec3, u: Vec2, shapes: &[Shape]) -> Option<EmitterSample> {
        match self {
            Emitter::Area { shape, radiance } => {
                let ds = shapes[*shape as usize].geometry.sample_direction(ref_p, u)?;
                // One-sided: the sampled point must face the reference point.
                if !(ds.d.dot(ds.n) < 0.0 && ds.pdf > 0.0) {
                    return None;
                }
                Some(EmitterSample {
                    d: ds.d,
                    dist: ds.dist,
                    pdf: ds.pdf,
                    delta: false,
                    weight: radiance.eval(ds.uv) / ds.pdf,
                    p: ds.p,
                    n: ds.n,
                })
            }
            Emitter::Point { position, intensity } => {
                let d = *position - ref_p;
                let dist2 = d.length_squared();
                let dist = dist2.sqrt();
                if dist == 0.0 {
                    return None;
                }
                let d = d / dist;
                Some(EmitterSample { d, dist, pdf: 1.0, delta: true, weight: *intensity / dist2, p: *position, n: -d })
            }
            Emitter::Spot {
                to_world,
                to_local,
                intensity,
                cutoff,
                beam_width,
                cos_cutoff,
                cos_beam,
                texture,
                uv_factor,
            } => {
                let pos: Vec3 = to_world.translation.into();
                let d = pos - ref_p;
                let dist2 = d.length_squared();
                let dist = dist2.sqrt();
                if dist == 0.0 {
                    return None;
                }
                let d = d / dist;
                let local_raw = to_local.transform_vector3(-d);
                let local = local_raw.normalize_or_zero();
                let falloff = spot_falloff(local.z, *cutoff, *beam_width, *cos_cutoff, *cos_beam);
                if falloff <= 0.0 {
                    return None;
                }
                let mut radiance = *intensity;
                if let Some(tex) = texture {
                    let uv = Vec2::new(local_raw.x, local_raw.y) / (local_raw.z * *uv_factor) * 0.5 + 0.5;
                    radiance *= tex.eval(uv);
                }
                Some(EmitterSample {
                    d,
                    dist,
                    pdf: 1.0,
                    delta: true,
                    weight: radiance * (falloff / dist2),
                    p: pos,
                    n: -d,
                })
            }
            Emitter::Directional { direction, irradiance } => {
                let d = -*direction;
                Some(EmitterSample {
                    d,
                    dist: f32::INFINITY,
                    pdf: 1.0,
                    delta: true,
                    weight: *irradiance,
                    p: ref_p + d,
                    n: *direction,
                })
            }
            Emitter::Projector { to_world, to_local, irradiance, tan_half, aspect, scale } => {
                let local = to_local.transform_point3(ref_p);
                if !(local.z > 0.0) {
                    return None;
                }
                // Inverse of the perspective camera's ray: image x grows towards local −x.
                let uv = Vec2::new(
                    0.5 * (1.0 - local.x / (local.z * tan_half)),
                    0.5 * (1.0 - local.y * aspect / (local.z * tan_half)),
                );
                if !(uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all()) {
                    return None;
                }
                let pos: Vec3 = to_world.translation.into();
                let n = to_world.transform_vector3(Vec3::Z);
                let d = pos - ref_p;
                let dist = d.length();
                let d = d / dist;
                let cos = -n.dot(d);
                let weight = irradiance.eval(uv) * (PI * scale / (local.z * local.z * cos));
                if !(cos > 0.0 && weight.is_finite()) {
                    return None;
                }
                Some(EmitterSample { d, dist, pdf: 1.0, delta: true, weight, p: pos, n })
            }
            Emitter::EnvMap(e) => {
                let (d, radiance, pdf) = e.sample(u)?;
                Some(EmitterSample {
                    d,
                    dist: f32::INFINITY,
                    pdf,
                    delta: false,
                    weight: radiance / pdf,
                    p: ref_p + d,
                    n: -d,
                })
            }
            Emitter::Constant { radiance } => {
                let d = warp::square_to_uniform_sphere(u);
                Some(EmitterSample {
                    d,
                    dist: f32::INFINITY,
                    pdf: warp::UNIFORM_SPHERE_PDF,
                    delta: false,
                    weight: *radiance / warp::UNIFORM_SPHERE_PDF,
                    p: ref_p + d,
                    n: -d,
                })
            }
        }
    }

    /// Whether this is the scene's environment (`constant` or `envmap`).
    #[inline]
    pub fn is_environment(&self) -> bool {
        matches!(self, Emitter::Constant { .. } | Emitter::EnvMap(_))
    }

    /// Radiance seen at a surface hit of this (area) emitter's shape.
    #[inline]
    pub fn eval_surface(&self, si: &SurfaceInteraction) -> Vec3 {
        match self {
            Emitter::Area { radiance, .. } if si.wi.z > 0.0 => radiance.eval(si),
            _ => Vec3::ZERO,
        }
    }

    /// Radiance of the environment for a ray escaping along `d`.
    #[inline]
    pub fn eval_environment(&self, d: Vec3) -> Vec3 {
        match self {
            Emitter::Constant { radiance } => *radiance,
            Emitter::EnvMap(e) => e.eval(d),
            _ => Vec3::ZERO,
        }
    }

    /// Solid-angle density with which light sampling picks the environment direction `d`.
    #[inline]
    pub fn pdf_environment(&self, d: Vec3) -> f32 {
        match self {
            Emitter::Constant { .. } => warp::UNIFORM_SPHERE_PDF,
            Emitter::EnvMap(e) => e.pdf(d),
            _ => 0.0,
        }
    }

    /// Solid-angle density of [`Self::sample_direction`] for an area-light hit `si` seen
    /// from `ref_p`, or for the environment (`si = None`). Zero for delta emitters.
    #[inline]
    pub fn pdf_direction(&self, ref_p: Vec3, si: Option<&SurfaceInteraction>, shapes: &[Shape]) -> f32 {
        match (self, si) {
            (Emitter::Area { shape, .. }, Some(si)) => shapes[*shape as usize].geometry.pdf_direction(ref_p, si),
            (Emitter::Constant { .. }, None) => warp::UNIFORM_SPHERE_PDF,
            _ => 0.0,
        }
    }
}

/// Mitsuba's spot falloff: 1 inside the beam, linear in the angle down to 0 at the cutoff,
/// 0 at and beyond it (strict `cos θ > cos cutoff`).
#[inline]
pub fn spot_falloff(cos_theta: f32, cutoff: f32, beam_width: f32, cos_cutoff: f32, cos_beam: f32) -> f32 {
    if cos_theta <= cos_cutoff {
        0.0
    } else if cos_theta >= cos_beam {
        1.0
    } else {
        ((cutoff - cos_theta.clamp(-1.0, 1.0).acos()) / (cutoff - beam_width)).clamp(0.0, 1.0)
    }
}

/// Spot-light constructor helper: angles in degrees as in the XML.
pub fn spot(to_world: Affine3A, intensity: Vec3, cutoff_deg: f32, beam_deg: f32, texture: Option<Texture>) -> Emitter {
    let cutoff = cutoff_deg.to_radians();
    let beam_width = beam_deg.to_radians();
    Emitter::Spot {
        to_world,
        to_local: to_world.inverse(),
        intensity,
        cutoff,
        beam_width,
        cos_cutoff: cutoff.cos(),
        cos_beam: beam_width.cos(),
        texture,
        uv_factor: cutoff.tan(),
    }
}
