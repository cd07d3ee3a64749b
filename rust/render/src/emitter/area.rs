//! Mitsuba's `area` emitter (`src/emitters/area.cpp`): `radiance` (an emitted colour or a uv
//! texture, not a mesh attribute; default 1) from the side its shape's shading normal points
//! to. Light samples come from the shape's own direction sampling; for the particle tracer
//! (on a triangle mesh) a uniform point (density 1/A; Mitsuba importance-samples a textured
//! radiance by its uv instead, which has the same expectation) and a cosine-weighted direction
//! about the normal, weight `L(uv)·π·A`.

use super::emitter_sample::{EmitterPosition, EmitterSample, LightRay};
use super::flags::EmitterFlags;
use super::light::Light;
use crate::geometry::Frame;
use crate::load::props::PluginProps;
use crate::shape::{Geometry, Shape, SurfaceInteraction};
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;
use std::f32::consts::PI;

/// An area light on shape `shape` of the scene.
#[derive(Clone, Debug)]
pub struct Area {
    /// Index of the shape in the scene.
    pub shape: u32,
    pub radiance: Texture,
}

impl Area {
    /// Reads an `area` emitter nested in shape `shape`. It follows its shape, so `to_world`
    /// is refused.
    pub(crate) fn from_props(p: &mut PluginProps, shape: u32) -> Result<Self, SceneError> {
        if p.has_property("to_world") {
            return Err(p.prop_err("to_world", "is not allowed on an area emitter (it follows its shape)"));
        }
        let radiance = p.emission_texture("radiance")?;
        if matches!(radiance, Texture::MeshAttribute(_)) {
            let c = p.child("radiance").expect("a nested texture");
            return Err(crate::load::err(
                c,
                "a mesh attribute as an emitter's radiance is not supported by matte render",
            ));
        }
        Ok(Area { shape, radiance })
    }
}

impl Light for Area {
    #[inline]
    fn flags(&self) -> EmitterFlags {
        EmitterFlags::SURFACE
    }

    #[inline]
    fn sample_direction(&self, ref_p: Vec3, u: Vec2, shapes: &[Shape]) -> Option<EmitterSample> {
        let ds = shapes[self.shape as usize].geometry.sample_direction(ref_p, u)?;
        // One-sided: the sampled point must face the reference point.
        if !(ds.d.dot(ds.n) < 0.0 && ds.pdf > 0.0) {
            return None;
        }
        let weight = self.radiance.eval(ds.uv) / ds.pdf;
        Some(EmitterSample { d: ds.d, dist: ds.dist, pdf: ds.pdf, delta: false, weight, p: ds.p, n: ds.n })
    }

    #[inline]
    fn pdf_direction(&self, ref_p: Vec3, si: Option<&SurfaceInteraction>, shapes: &[Shape]) -> f32 {
        si.map_or(0.0, |si| shapes[self.shape as usize].geometry.pdf_direction(ref_p, si))
    }

    #[inline]
    fn eval_surface(&self, si: &SurfaceInteraction) -> Vec3 {
        if si.wi.z > 0.0 { self.radiance.eval(si) } else { Vec3::ZERO }
    }

    #[inline]
    fn can_sample_ray(&self, shapes: &[Shape]) -> bool {
        matches!(shapes[self.shape as usize].geometry, Geometry::Triangles(_))
    }

    /// A uniform point on the shape's mesh.
    #[inline]
    fn sample_position(&self, u: Vec2, shapes: &[Shape]) -> Option<EmitterPosition> {
        let Geometry::Triangles(t) = &shapes[self.shape as usize].geometry else { return None };
        let (p, n, uv) = t.sample_position(u)?;
        Some(EmitterPosition { p, n, weight: self.radiance.eval(uv) * t.surface_area() })
    }

    #[inline]
    fn sample_ray(&self, u_pos: Vec2, u_dir: Vec2, shapes: &[Shape]) -> Option<LightRay> {
        let ep = self.sample_position(u_pos, shapes)?;
        let local = matte_brdf::sampling::square_to_cosine_hemisphere(u_dir);
        let d = Frame::from_normal(ep.n).to_world(local);
        Some(LightRay { o: ep.p, d, n: Some(ep.n), weight: ep.weight * PI })
    }
}
