//! The renderer (`rust/render`): its scene loader (the Mitsuba object tree to a renderable
//! scene, `load`, `mesh_attributes`), shapes and ray queries, emitters, textures, BSDFs, film
//! and image files, samplers, integrators and tile drivers.

#[path = "../common/mod.rs"]
mod common;

mod accel_backends;
mod axis_aligned_rays;
mod bitmap;
mod envmap;
mod film;
mod load;
mod matte_bsdf;
mod mesh_attributes;
mod mitsuba_bsdfs;
mod particle_tracer;
mod render_core;
mod render_drivers;
mod samplers;
mod shading_frames;
mod specular_bsdfs;
mod volume_texture;
