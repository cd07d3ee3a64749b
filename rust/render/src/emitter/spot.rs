//! Mitsuba's `spot` emitter (`src/emitters/spot.cpp`): a point light at `to_world`'s origin
//! shining along its local +z with `intensity` I (default 1); the falloff is 1 inside
//! `beam_width`, linear in the angle down to 0 at `cutoff_angle` (degrees; defaults 20 and
//! ¾·cutoff). An optional `texture` multiplies the intensity, looked up at uv = ½ + ½·(x,
//! y)/(z·tan cutoff) of the local direction (`direction_to_uv`). For the particle tracer a
//! uniform direction in the cutoff cone, weight `I·texture(uv)·falloff/pdf`.

use super::emitter_sample::{EmitterSample, LightRay};
use super::flags::EmitterFlags;
use super::light::Light;
use crate::geometry::warp;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::Shape;
use crate::texture::Texture;
use glam::{Affine3A, Vec2, Vec3};
use matte_scene_file::SceneError;

/// Spot light; angles in radians.
#[derive(Clone, Debug)]
pub struct Spot {
    pub to_world: Affine3A,
    to_local: Affine3A,
    pub intensity: Vec3,
    pub cutoff: f32,
    pub beam_width: f32,
    cos_cutoff: f32,
    cos_beam: f32,
    texture: Option<Texture>,
    uv_factor: f32,
}

impl Spot {
    /// A spot light with its angles in degrees, as in the XML.
    #[must_use]
    pub fn new(to_world: Affine3A, intensity: Vec3, cutoff_deg: f32, beam_deg: f32, texture: Option<Texture>) -> Self {
        let cutoff = cutoff_deg.to_radians();
        let beam_width = beam_deg.to_radians();
        Spot {
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

    /// Mitsuba's falloff: 1 inside the beam, linear in the angle down to 0 at the cutoff,
    /// 0 at and beyond it (strict `cos θ > cos cutoff`).
    #[inline]
    fn falloff(&self, cos_theta: f32) -> f32 {
        if cos_theta <= self.cos_cutoff {
            0.0
        } else if cos_theta >= self.cos_beam {
            1.0
        } else {
            ((self.cutoff - cos_theta.clamp(-1.0, 1.0).acos()) / (self.cutoff - self.beam_width)).clamp(0.0, 1.0)
        }
    }

    /// `weight` times the texture towards the local direction `local` (not normalised).
    #[inline]
    fn textured(&self, weight: Vec3, local: Vec3) -> Vec3 {
        match &self.texture {
            Some(tex) => weight * tex.eval(Vec2::new(local.x, local.y) / (local.z * self.uv_factor) * 0.5 + 0.5),
            None => weight,
        }
    }
}

impl FromProps for Spot {
    /// `texture` (`get_texture`, default 1) must vary spatially when given.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let intensity = p.emission("intensity")?;
        let cutoff = p.float("cutoff_angle")?;
        let beam = p.float_or("beam_width", cutoff * 0.75)?;
        if !(cutoff > 0.0 && cutoff <= 180.0 && beam > 0.0 && beam <= cutoff) {
            return Err(p.err(format!("needs 0 < beam_width ({beam}) ≤ cutoff_angle ({cutoff}) ≤ 180")));
        }
        let texture = match p.child("texture") {
            None => None,
            Some(c) if c.tag == "texture" => Some(crate::load::texture::build_for_emitter(p.builder(), c, "texture")?),
            Some(c) => return Err(crate::load::err(c, "\"texture\" must be a texture (e.g. bitmap)")),
        };
        if p.has_property("texture") {
            return Err(p.prop_err("texture", "must be spatially varying (e.g. bitmap type), as in Mitsuba"));
        }
        Ok(Spot::new(p.transform("to_world")?, intensity, cutoff as f32, beam as f32, texture))
    }
}

impl Light for Spot {
    #[inline]
    fn flags(&self) -> EmitterFlags {
        EmitterFlags::DELTA_POSITION
    }

    #[inline]
    fn sample_direction(&self, ref_p: Vec3, _u: Vec2, _shapes: &[Shape]) -> Option<EmitterSample> {
        let pos: Vec3 = self.to_world.translation.into();
        let d = pos - ref_p;
        let dist2 = d.length_squared();
        let dist = dist2.sqrt();
        if dist == 0.0 {
            return None;
        }
        let d = d / dist;
        let local = self.to_local.transform_vector3(-d);
        let falloff = self.falloff(local.normalize_or_zero().z);
        if falloff <= 0.0 {
            return None;
        }
        let weight = self.textured(self.intensity, local) * (falloff / dist2);
        Some(EmitterSample { d, dist, pdf: 1.0, delta: true, weight, p: pos, n: -d })
    }

    #[inline]
    fn can_sample_ray(&self, _shapes: &[Shape]) -> bool {
        true
    }

    #[inline]
    fn sample_ray(&self, u_pos: Vec2, _u_dir: Vec2, _shapes: &[Shape]) -> Option<LightRay> {
        let local = warp::square_to_uniform_cone(u_pos, self.cos_cutoff);
        let weight = self.intensity * (self.falloff(local.z) / warp::uniform_cone_pdf(self.cos_cutoff));
        let weight = self.textured(weight, local);
        let d = self.to_world.transform_vector3(local).normalize();
        Some(LightRay { o: self.to_world.translation.into(), d, n: None, weight })
    }
}
