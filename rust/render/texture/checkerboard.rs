//! Mitsuba's `checkerboard` texture (`src/textures/checkerboard.cpp`): with
//! uv' = to_uv · uv, `color0` where the fractional parts of u' and v' are both above or both
//! at most 1/2, else `color1` (defaults 0.4 and 0.2). Both colours are textures themselves.

use crate::render::bsdf::Texture;
use glam::{Affine2, Vec2, Vec3};

#[derive(Clone, Debug)]
pub struct Checkerboard {
    pub color0: Texture,
    pub color1: Texture,
    pub to_uv: Affine2,
}

impl Checkerboard {
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Vec3 {
        let t = self.to_uv.transform_point2(uv);
        let f = t - t.floor();
        if (f.x > 0.5) == (f.y > 0.5) { self.color0.eval(uv) } else { self.color1.eval(uv) }
    }
}
