//! Textures (`src/textures/*.cpp`): `bitmap` (§11), `checkerboard`, `mesh_attribute` and
//! `volume` (with its `gridvolume` and `constvolume`), and [`Texture`], what a BSDF or emitter
//! parameter holds (a constant or one of those).

mod bitmap;
mod bitmap_load;
mod checkerboard;
mod mesh_attribute;
mod parameter;
pub(crate) mod volume;

pub use bitmap::{BitmapFilter, BitmapOptions, BitmapTexture, WrapMode};
pub use bitmap_load::srgb_to_linear;
pub use checkerboard::Checkerboard;
pub use mesh_attribute::BoundAttribute;
pub use parameter::{TexPoint, Texture};
pub use volume::{GridFilter, GridVolume, Volume, VolumeData, VolumeGrid};
