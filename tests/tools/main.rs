//! The `matte` commands beside `render`: `brdf` and `albedo` (`rust/matte/src/cli`), `validate`'s
//! statistics (`rust/matte/src/validate`), `study` (`rust/matte/src/study`), `bench` (`rust/matte/src/bench`) and the virtual
//! gonioreflectometer (`rust/matte/src/microgeometry`).

#[path = "../common/mod.rs"]
mod common;

mod bench;
mod cli;
mod ground_truth_tables;
mod inventories;
mod microgeometry;
mod render_cli;
mod study;
mod study_scenes;
mod validate_stats;
