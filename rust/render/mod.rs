//! The Rust path tracer: reads the same Mitsuba XML scenes as Mitsuba 3.9.1 and produces the
//! same expected image (`shared/docs/mitsuba-semantics.md`).

pub mod bsdf;
pub mod film;
pub mod image_io;
pub mod texture;
