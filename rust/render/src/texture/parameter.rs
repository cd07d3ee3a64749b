//! A BSDF parameter that is either a constant RGB, a `bitmap` texture looked up at the
//! hit's uv, a `checkerboard`, a mesh's attribute (`mesh_attribute`) at the hit, or a
//! `volume` texture at the hit's world-space position (Mitsuba `get_texture`). A constant is
//! also what the `rawconstant` plugin reads ([`Texture::raw_constant_from_props`]).

use super::bitmap::BitmapTexture;
use super::checkerboard::Checkerboard;
use super::mesh_attribute::BoundAttribute;
use super::volume::Volume;
use crate::load::props::PluginProps;
use crate::shape::SurfaceInteraction;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;
use matte_scene_file::xml::Value;
use std::sync::Arc;

#[derive(Clone, Debug)]
pub enum Texture {
    Constant(Vec3),
    Bitmap(Arc<BitmapTexture>),
    Checkerboard(Checkerboard),
    /// `mesh_attribute`, bound to the attribute of the shape it belongs to.
    MeshAttribute(BoundAttribute),
    /// `volume`: a `gridvolume` or `constvolume` looked up at the world-space hit point.
    Volume(Arc<Volume>),
}

impl Texture {
    /// Mitsuba's `rawconstant` (`src/spectra/rawconstant.cpp`): `value`, a `<float>` (all three
    /// channels) or a `<vector>`, used as is (no colour conversion, no range check): the
    /// [`Texture::Constant`]'s value.
    pub(crate) fn raw_constant_from_props(p: &mut PluginProps) -> Result<Vec3, SceneError> {
        let value = match p.raw("value") {
            None => return Err(p.err("missing required parameter \"value\" (a float or a 3-D vector)")),
            Some(Value::Vector(_) | Value::Point(_)) => p.point_opt("value")?.unwrap_or_default(),
            Some(Value::Float(_) | Value::Integer(_)) => Vec3::splat(p.float_opt("value")?.unwrap_or_default() as f32),
            Some(other) => {
                let message = format!("has the wrong type (expected float or vector, found {})", other.type_name());
                return Err(p.prop_err("value", message));
            }
        };
        if !value.is_finite() {
            return Err(p.prop_err("value", "must be finite"));
        }
        Ok(value)
    }
}

/// Where a texture is looked up: the uv, for mesh attributes the hit triangle and its
/// barycentrics, for volume textures the world-space point. Built from a
/// [`SurfaceInteraction`], or from a bare uv (emitters, tests: triangle 0 at barycentrics
/// (0, 0), the point at the origin; the loader refuses volume textures where only a uv is
/// known).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TexPoint {
    pub uv: Vec2,
    pub prim: u32,
    pub bary: Vec2,
    pub p: Vec3,
}

impl From<Vec2> for TexPoint {
    #[inline]
    fn from(uv: Vec2) -> Self {
        TexPoint { uv, prim: 0, bary: Vec2::ZERO, p: Vec3::ZERO }
    }
}

impl From<&SurfaceInteraction> for TexPoint {
    #[inline]
    fn from(si: &SurfaceInteraction) -> Self {
        TexPoint { uv: si.uv, prim: si.prim, bary: si.bary, p: si.p }
    }
}

impl Texture {
    /// The value of a constant, `None` for any other texture.
    #[must_use]
    pub fn constant(&self) -> Option<Vec3> {
        match self {
            Texture::Constant(c) => Some(*c),
            _ => None,
        }
    }

    /// Whether a lookup needs the surface point (the triangle for a mesh attribute, the
    /// world-space point for a volume texture), not only the uv.
    #[must_use]
    pub fn needs_surface_point(&self) -> bool {
        matches!(self, Texture::MeshAttribute(_) | Texture::Volume(_))
    }

    #[inline]
    pub fn eval(&self, at: impl Into<TexPoint>) -> Vec3 {
        let at = at.into();
        match self {
            Texture::Constant(c) => *c,
            Texture::Bitmap(b) => b.eval(at.uv),
            Texture::Checkerboard(c) => c.eval(at.uv),
            Texture::MeshAttribute(a) => a.eval(at.prim, at.bary),
            Texture::Volume(v) => v.eval(at.p),
        }
    }

    /// Mitsuba's `Texture::eval_1` in RGB mode (a scalar parameter such as a roughness): the
    /// channel mean of a constant (`srgb`'s `eval_1` returns its `mean()`; a `<float>` is the
    /// same value in all channels), the luminance of a bitmap's RGB, and the checkerboard's
    /// own `eval_1` (which swaps the two colours' places, see [`Checkerboard`]), and a volume's
    /// `eval_1` (see [`Volume::eval_1`]).
    #[inline]
    pub fn eval_1(&self, at: impl Into<TexPoint>) -> f32 {
        let at = at.into();
        match self {
            Texture::Constant(c) => (c.x + c.y + c.z) / 3.0,
            Texture::Bitmap(b) => b.eval(at.uv).dot(Vec3::new(0.212_671, 0.715_160, 0.072_169)),
            Texture::Checkerboard(c) => c.eval_1(at.uv),
            Texture::MeshAttribute(a) => a.eval_1(at.prim, at.bary),
            Texture::Volume(v) => v.eval_1(at.p),
        }
    }

    /// Mitsuba's `Texture::eval_1_grad`: zero for a constant, the bilinear luminance gradient
    /// for a bitmap, zero for a checkerboard (piecewise constant), a mesh attribute and a
    /// volume (the loader refuses them where a gradient is needed).
    #[inline]
    pub fn eval_1_grad(&self, at: impl Into<TexPoint>) -> Vec2 {
        match self {
            Texture::Constant(_) | Texture::Checkerboard(_) | Texture::MeshAttribute(_) | Texture::Volume(_) => {
                Vec2::ZERO
            }
            Texture::Bitmap(b) => b.eval_1_grad(at.into().uv),
        }
    }

    /// Mitsuba's `Texture::mean()` in RGB mode: the mean of the three channels for a constant
    /// (`srgb`/`uniform` spectra), the texels' mean luminance for a bitmap. Plastics use it
    /// for their lobe-selection weight. Mitsuba's volume texture has none (the loader refuses
    /// it where Mitsuba asks for it); matte's is [`Volume::mean`].
    pub fn mean(&self) -> f32 {
        match self {
            Texture::Constant(c) => (c.x + c.y + c.z) / 3.0,
            Texture::Bitmap(b) => b.mean_luminance(),
            Texture::Checkerboard(c) => c.mean(),
            Texture::MeshAttribute(a) => a.mean(),
            Texture::Volume(v) => v.mean(),
        }
    }
}
