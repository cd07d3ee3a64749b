//! The Mitsuba XML layer and the mesh formats (`rust/scene_file`): the tests of
//! `matte-scene-file`, which link nothing above it. The loader's tests, which turn the object
//! tree into a renderable scene, are the renderer's (`tests/render/load.rs` and `tests/render/load/`).

#[path = "../common/paths.rs"]
mod common;

mod mesh;
mod xml;
