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
}
