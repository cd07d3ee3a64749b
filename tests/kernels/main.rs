//! The diffuse BRDF models (`rust/brdf`): the kernels against closed forms, independent f64
//! evaluations and the reference tables; their sampling, parameters and per-lane forms.

#[path = "../common/kernels.rs"]
mod common;

mod burley;
mod chi_square;
mod ginneken_fast_path;
mod kernel_precision;
mod parameters;
mod properties;
mod reference_tables;
mod registry;
mod rough_diffuse;
mod sampling;
mod simd_kernels;
mod tabulated_brdf;
mod textured_parameters;
