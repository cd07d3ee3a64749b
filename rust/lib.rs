//! matte: diffuse reflection models for global illumination (Lambert, Oren–Nayar, EON,
//! Wolff, van Ginneken et al.), as studied by Diepstraten & Borgo (EG 2006 short papers).
//!
//! * [`brdf`]: the kernels, one pure implementation per model, used by everything else.
//! * [`cli`]: the `matte` command line (`brdf`, `albedo`, `tables`, `render`, `validate`, `study`, `bench`).
//! * [`ffi`]: the `cxx` bridge the Mitsuba plugin (`cpp/`) calls.
//! * [`scene_file`]: Mitsuba XML scenes → typed description (parser, properties, meshes).
//! * [`render`]: the CPU path tracer that renders them.
//! * [`validate`]: per-pixel statistical comparison of the Rust renderer with Mitsuba.
//! * [`study`]: the seed paper's experiment (scenes × models, strips, measured ratios).
//! * [`bench`]: the speed targets, matte against Mitsuba in one run (`matte bench`).
//! * [`installation`]: where the Python side (Mitsuba) and the package data are found at run time.
//! * [`markup`]: escaping for the HTML reports and derived XML scenes.
//! * [`microgeometry`]: the virtual gonioreflectometer (ground truth for the rough models).

// `!(x > 0.0)` is deliberate throughout: it is true for NaN as well, which is what the
// guards against degenerate samples and bad parameters need.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod bench;
pub mod brdf;
pub mod cli;
pub mod ffi;
pub mod installation;
pub mod markup;
pub mod microgeometry;
pub mod render;
pub mod scene_file;
pub mod study;
pub mod validate;
