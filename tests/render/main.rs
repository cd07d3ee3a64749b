//! The renderer (`rust/render` beside its loader): shapes and ray queries, emitters, textures,
//! BSDFs, film and image files, samplers, integrators and tile drivers.

#[path = "../common/mod.rs"]
mod common;

mod accel_backends;
mod axis_aligned_rays;
mod bitmap;
mod envmap;
mod film;
mod matte_bsdf;
mod mitsuba_bsdfs;
mod particle_tracer;
mod render_core;
mod render_drivers;
mod samplers;
mod shading_frames;
mod specular_bsdfs;
mod volume_texture;
