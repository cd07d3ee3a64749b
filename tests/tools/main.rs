//! The `matte` commands beside `render`: `brdf` and `albedo` (`rust/cli`), `validate`'s
//! statistics (`rust/validate`), `study` (`rust/study`), `bench` (`rust/bench`) and the virtual
//! gonioreflectometer (`rust/microgeometry`).

#[path = "../common/mod.rs"]
mod common;

mod bench;
mod cli;
mod ground_truth_tables;
mod inventories;
mod microgeometry;
mod study;
mod study_scenes;
mod validate_stats;
