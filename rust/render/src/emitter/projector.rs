//! Mitsuba's `projector` emitter (`src/emitters/projector.cpp`): a pinhole at `to_world`'s
//! origin casting the `irradiance` texture (an emitted colour or a uv texture, default 1)
//! along local +z, times `scale` (default 1), over the field of view of `perspective` (`fov` +
//! `fov_axis`, or `focal_length`, default 50mm) at the texture's aspect ratio (1 for a
//! colour). Irradiance at local depth 1 on a plane facing it is π·scale·texture. For the
//! particle tracer a uniform point of the texture (Mitsuba samples it by luminance: same
//! expectation) and the direction through it; weight `E(uv)·scale·π·A_image`, with A_image
//! the image rectangle's area at unit distance.

use super::emitter_sample::{EmitterSample, LightRay};
use super::flags::EmitterFlags;
use super::light::Light;
use crate::load::props::{FromProps, PluginProps};
use crate::sensor::{field_of_view, x_half_tan};
use crate::shape::Shape;
use crate::texture::Texture;
use glam::{Affine3A, Vec2, Vec3};
use matte_scene_file::SceneError;
use std::f32::consts::PI;

/// Projector: x half-angle tangent `tan_half` over an image of aspect `aspect`.
#[derive(Clone, Debug)]
pub struct Projector {
    to_world: Affine3A,
    to_local: Affine3A,
    irradiance: Texture,
    tan_half: f32,
    aspect: f32,
    scale: f32,
}

impl FromProps for Projector {
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let irradiance = p.emission_texture("irradiance")?;
        let aspect = match &irradiance {
            Texture::Bitmap(bm) => {
                let [w, h] = bm.resolution();
                w as f64 / h as f64
            }
            _ => 1.0,
        };
        let (scale, to_world) = scale_and_to_world(p)?;
        let (fov_deg, axis) = field_of_view(p)?;
        let tan_half = x_half_tan(fov_deg, axis, aspect) as f32;
        let to_local = to_world.inverse();
        Ok(Projector { to_world, to_local, irradiance, tan_half, aspect: aspect as f32, scale: scale as f32 })
    }
}

/// `scale` (finite, default 1) and an invertible `to_world`, as `envmap` and `projector` read
/// them.
pub(super) fn scale_and_to_world(p: &mut PluginProps) -> Result<(f64, Affine3A), SceneError> {
    let scale = p.float("scale")?;
    if !scale.is_finite() {
        return Err(p.prop_err("scale", "must be finite"));
    }
    let to_world = p.transform("to_world")?;
    if to_world.matrix3.determinant() == 0.0 {
        return Err(p.prop_err("to_world", "must be invertible"));
    }
    Ok((scale, to_world))
}

impl Light for Projector {
    #[inline]
    fn flags(&self) -> EmitterFlags {
        EmitterFlags::DELTA_POSITION
    }

    #[inline]
    fn sample_direction(&self, ref_p: Vec3, _u: Vec2, _shapes: &[Shape]) -> Option<EmitterSample> {
        let local = self.to_local.transform_point3(ref_p);
        if !(local.z > 0.0) {
            return None;
        }
        // Inverse of the perspective camera's ray: image x grows towards local −x.
        let uv = Vec2::new(
            0.5 * (1.0 - local.x / (local.z * self.tan_half)),
            0.5 * (1.0 - local.y * self.aspect / (local.z * self.tan_half)),
        );
        if !(uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all()) {
            return None;
        }
        let pos: Vec3 = self.to_world.translation.into();
        let n = self.to_world.transform_vector3(Vec3::Z);
        let d = pos - ref_p;
        let dist = d.length();
        let d = d / dist;
        let cos = -n.dot(d);
        let weight = self.irradiance.eval(uv) * (PI * self.scale / (local.z * local.z * cos));
        if !(cos > 0.0 && weight.is_finite()) {
            return None;
        }
        Some(EmitterSample { d, dist, pdf: 1.0, delta: true, weight, p: pos, n })
    }

    #[inline]
    fn can_sample_ray(&self, _shapes: &[Shape]) -> bool {
        true
    }

    #[inline]
    fn sample_ray(&self, _u_pos: Vec2, u_dir: Vec2, _shapes: &[Shape]) -> Option<LightRay> {
        let (uv, t) = (u_dir, self.tan_half);
        let local = Vec3::new((1.0 - 2.0 * uv.x) * t, (1.0 - 2.0 * uv.y) * t / self.aspect, 1.0);
        let d = self.to_world.transform_vector3(local.normalize()).normalize();
        let image_area = 4.0 * t * t / self.aspect;
        let weight = self.irradiance.eval(uv) * (self.scale * PI * image_area);
        Some(LightRay { o: self.to_world.translation.into(), d, n: None, weight })
    }
}
