//! Scene files: the Mitsuba XML layer and the mesh formats (`rust/scene_file`), and the loader
//! that turns the object tree into a renderable scene (`rust/render/load`).

#[path = "../common/mod.rs"]
mod common;

mod load;
mod mesh;
mod mesh_attributes;
mod xml;
