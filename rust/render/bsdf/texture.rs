//! A BSDF parameter that is either a constant RGB or a `bitmap` texture looked up at the
//! hit's uv (Mitsuba `get_texture`).

use glam::{Vec2, Vec3};

#[derive(Clone, Debug)]
pub enum Texture {
    Constant(Vec3),
}

impl Texture {
    #[inline]
    pub fn eval(&self, _uv: Vec2) -> Vec3 {
        match self {
            Texture::Constant(c) => *c,
        }
    }
}
