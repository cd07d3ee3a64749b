//! Mitsuba's `checkerboard` texture (`src/textures/checkerboard.cpp`, v3.9.1).
//!
//! With uv' = `to_uv`·uv and the per-axis test fract(uv') > ½:
//! * `eval` (colours) gives `color0` where both tests agree, `color1` where they differ;
//! * pitfall: `eval_1` (scalar parameters such as a roughness or an opacity) uses the
//!   **opposite** test, `color0` where they differ, and each colour's `eval_1` is the mean of
//!   its channels (`srgb`'s `eval_1` is its `mean()`);
//! * `mean()` is the average of the two colours' channel means.
//!
//! docs/renderer-semantics.md §11 (checkerboard).

use crate::load::props::{FromProps, PluginProps};
use glam::{Affine2, Vec2, Vec3};
use matte_scene_file::SceneError;

#[derive(Clone, Debug, PartialEq)]
pub struct Checkerboard {
    pub color0: Vec3,
    pub color1: Vec3,
    pub to_uv: Affine2,
}

impl Checkerboard {
    /// Whether fract(u') and fract(v') are on the same side of ½.
    #[inline]
    fn same_half(&self, uv: Vec2) -> bool {
        let p = self.to_uv.transform_point2(uv);
        let f = p - p.floor();
        (f.x > 0.5) == (f.y > 0.5)
    }

    /// Mitsuba's `Checkerboard::eval`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Vec3 {
        if self.same_half(uv) { self.color0 } else { self.color1 }
    }

    /// Mitsuba's `Checkerboard::eval_1`: the other assignment of the two colours.
    #[inline]
    pub fn eval_1(&self, uv: Vec2) -> f32 {
        let c = if self.same_half(uv) { self.color1 } else { self.color0 };
        channel_mean(c)
    }

    /// Mitsuba's `Checkerboard::mean`.
    pub fn mean(&self) -> f32 {
        0.5 * (channel_mean(self.color0) + channel_mean(self.color1))
    }
}

#[inline]
fn channel_mean(c: Vec3) -> f32 {
    (c.x + c.y + c.z) / 3.0
}

impl FromProps for Checkerboard {
    /// `color0` and `color1` (colours, defaults 0.4 and 0.2) and `to_uv`. Textured colours
    /// are not supported.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let mut colour = |name: &str| -> Result<Vec3, SceneError> {
            match p.texture(name)?.constant() {
                Some(c) => Ok(c),
                None => {
                    Err(p.err(format!("\"{name}\" must be a colour (a textured {name} is not supported by matte)")))
                }
            }
        };
        let (color0, color1) = (colour("color0")?, colour("color1")?);
        let to_uv = p.uv_transform("to_uv")?;
        Ok(Checkerboard { color0, color1, to_uv })
    }
}
