//! A BSDF parameter that is either a constant RGB, a `bitmap` texture looked up at the
//! hit's uv or a `checkerboard` (Mitsuba `get_texture`).

use crate::render::texture::{BitmapTexture, Checkerboard};
use glam::{Vec2, Vec3};
use std::sync::Arc;

#[derive(Clone, Debug)]
pub enum Texture {
    Constant(Vec3),
    Bitmap(Arc<BitmapTexture>),
    Checkerboard(Checkerboard),
}

impl Texture {
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Vec3 {
        match self {
            Texture::Constant(c) => *c,
            Texture::Bitmap(b) => b.eval(uv),
            Texture::Checkerboard(c) => c.eval(uv),
        }
    }

    /// Mitsuba's `Texture::eval_1` in RGB mode (a scalar parameter such as a roughness): the
    /// channel mean of a constant (`srgb`'s `eval_1` returns its `mean()`; a `<float>` is the
    /// same value in all channels), the luminance of a bitmap's RGB, and the checkerboard's
    /// own `eval_1` (which swaps the two colours' places, see [`Checkerboard`]).
    #[inline]
    pub fn eval_1(&self, uv: Vec2) -> f32 {
        match self {
            Texture::Constant(c) => (c.x + c.y + c.z) / 3.0,
            Texture::Bitmap(b) => b.eval(uv).dot(Vec3::new(0.212_671, 0.715_160, 0.072_169)),
            Texture::Checkerboard(c) => c.eval_1(uv),
        }
    }

    /// Mitsuba's `Texture::eval_1_grad`: zero for a constant, the bilinear luminance gradient
    /// for a bitmap, zero for a checkerboard (piecewise constant).
    #[inline]
    pub fn eval_1_grad(&self, uv: Vec2) -> Vec2 {
        match self {
            Texture::Constant(_) | Texture::Checkerboard(_) => Vec2::ZERO,
            Texture::Bitmap(b) => b.eval_1_grad(uv),
        }
    }

    /// Mitsuba's `Texture::mean()` in RGB mode: the mean of the three channels for a constant
    /// (`srgb`/`uniform` spectra), the texels' mean luminance for a bitmap. Plastics use it
    /// for their lobe-selection weight.
    pub fn mean(&self) -> f32 {
        match self {
            Texture::Constant(c) => (c.x + c.y + c.z) / 3.0,
            Texture::Bitmap(b) => b.mean_luminance(),
            Texture::Checkerboard(c) => c.mean(),
        }
    }
}
