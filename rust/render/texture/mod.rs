//! Textures (`src/textures/*.cpp`): `bitmap` (§11; the loader also builds `checkerboard` as a
//! 2×2 nearest-lookup bitmap, `load/texture.rs`); uniform colours stay
//! plain values in the scene description.

mod bitmap;
mod bitmap_load;

pub use bitmap::{BitmapFilter, BitmapOptions, BitmapTexture, WrapMode};
pub use bitmap_load::srgb_to_linear;
