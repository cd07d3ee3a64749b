//! Textures (`src/textures/*.cpp`): `bitmap` (§11), `checkerboard` and `mesh_attribute`;
//! uniform colours stay plain values in the scene description.

mod bitmap;
mod bitmap_load;
mod checkerboard;
mod mesh_attribute;

pub use bitmap::{BitmapFilter, BitmapOptions, BitmapTexture, WrapMode};
pub use bitmap_load::srgb_to_linear;
pub use checkerboard::Checkerboard;
pub use mesh_attribute::BoundAttribute;
