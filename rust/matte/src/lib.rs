//! matte: diffuse reflection models for global illumination (Lambert, Oren–Nayar, EON,
//! Wolff, van Ginneken et al.), as studied by Diepstraten & Borgo (EG 2006 short papers).
//!
//! This crate is the top of the workspace: the `matte` command and the harness around the
//! renderer. Beneath it, each its own crate:
//! * `matte_brdf` (`rust/brdf/`): the kernels, one pure implementation per model, used by
//!   everything else;
//! * `matte_plugin` (`rust/plugin/src/`): the `cxx` bridge the Mitsuba plugin (`cpp/`) links;
//! * `matte_scene_file` (`rust/scene_file/`): Mitsuba XML scenes → typed description (parser,
//!   properties, meshes);
//! * `matte_render` (`rust/render/`): the CPU path tracer that renders them.
//!
//! Here:
//! * [`cli`]: the `matte` command line (`brdf`, `albedo`, `tables`, `render`, `validate`, `study`, `bench`).
//! * [`validate`]: per-pixel statistical comparison of the Rust renderer with Mitsuba.
//! * [`study`]: the seed paper's experiment (scenes × models, strips, measured ratios).
//! * [`bench`]: the speed targets, matte against Mitsuba in one run (`matte bench`).
//! * [`installation`]: where the Python side (Mitsuba) and the package data are found at run time.
//! * [`markup`]: escaping for the HTML reports and derived XML scenes.
//! * [`microgeometry`]: the virtual gonioreflectometer (ground truth for the rough models).

pub mod bench;
pub mod cli;
pub mod installation;
pub mod markup;
pub mod microgeometry;
pub mod study;
pub mod validate;
