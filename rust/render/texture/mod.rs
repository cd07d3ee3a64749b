//! Textures (`src/textures/*.cpp`). Only `bitmap` so far (§11); uniform colours stay plain
//! values in the scene description.

mod bitmap;
mod bitmap_load;

pub use bitmap::{BitmapFilter, BitmapOptions, BitmapTexture, WrapMode};
pub use bitmap_load::srgb_to_linear;
