//! A BSDF parameter that is either a constant RGB or a `bitmap` texture looked up at the
//! hit's uv (Mitsuba `get_texture`).

use crate::render::texture::BitmapTexture;
use glam::{Vec2, Vec3};
use std::sync::Arc;

#[derive(Clone, Debug)]
pub enum Texture {
    Constant(Vec3),
    Bitmap(Arc<BitmapTexture>),
}

impl Texture {
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Vec3 {
        match self {
            Texture::Constant(c) => *c,
            Texture::Bitmap(b) => b.eval(uv),
        }
    }

    /// Mitsuba's `Texture::mean()` in RGB mode: the mean of the three channels for a constant
    /// (`srgb`/`uniform` spectra), the texels' mean luminance for a bitmap. Plastics use it
    /// for their lobe-selection weight.
    pub fn mean(&self) -> f32 {
        match self {
            Texture::Constant(c) => (c.x + c.y + c.z) / 3.0,
            Texture::Bitmap(b) => b.mean_luminance(),
        }
    }
}
