//! The Rust path tracer: reads the same Mitsuba XML scenes as Mitsuba 3.9.1 and produces the
//! same expected image (`docs/renderer-semantics.md`).
//!
//! Data flow: [`matte_scene_file`] reads the XML (and meshes) into an object tree → [`load`]
//! builds a [`scene::Scene`] (shapes, BSDFs, emitters, ray queries) plus camera ([`sensor`]),
//! film, sampler and integrator → [`renderer`] runs the integrator per pixel sample in parallel
//! tiles and splats into the film.

/// `T` for `Box<T>`, `Arc<T>` and `T`: the type an enum variant stores, boxed, shared or
/// neither (for the forwarding macros that declare [`bsdf::Bsdf`] and [`emitter::Emitter`]).
macro_rules! stored_type {
    (Box<$t:ty>) => {
        $t
    };
    (Arc<$t:ty>) => {
        $t
    };
    ($t:ty) => {
        $t
    };
}

pub mod accel;
pub mod bsdf;
pub mod emitter;
pub mod film;
pub mod geometry;
pub mod image_io;
pub mod integrator;
pub mod load;
pub mod renderer;
pub mod sampler;
pub mod scene;
pub mod sensor;
pub mod shape;
pub mod texture;
