//! The registry of diffuse models, by concern: [`spec`] (the declarations), [`values`]
//! (reading and reporting parameter values), [`flat`] (values as slices), [`registered`] (what a
//! model implements), [`list`] (the `models!` list and what it generates), [`brdf`] (a kernel as
//! a BRDF).
//!
//! Each model declares itself once, in its own file under `rust/brdf/src/models/`: a
//! [`ModelSpec`] (plugin name, parameters with kind, default, valid range and the clamp of
//! its per-lane values, example configurations) and an implementation of [`Registered`]
//! (how its kernel is built from those parameters). The list of models is the one
//! `models!` call in `rust/brdf/src/models/mod.rs`; from it come [`super::DiffuseModel`] and its
//! static dispatch (`dispatch!`), [`super::LaneKernel`], [`super::MODELS`],
//! [`super::BSDF_TYPES`], the parameter parsing of every front end (CLI, scene loader,
//! Mitsuba plugin) and `matte types --json`, which the Python side and the tests read.
//! `docs/adding-a-model.md` walks through adding one.

pub mod brdf;
pub mod flat;
pub mod list;
pub mod registered;
pub mod spec;
pub mod values;

pub use brdf::KernelBrdf;
pub(crate) use flat::flat_values;
pub use flat::{Flat, NoValues};
pub(crate) use list::models;
pub use registered::{Evaluation, Gradients, Registered, clamp_lanes};
pub use spec::{MAX_NUMERIC, ModelSpec, ParamKind, ParamSpec, Range, fits_are_valid, numeric_count};
pub use values::{Param, Values, index_of, kind, names_all_parameters, names_numeric_parameters};
pub(crate) use values::{param, parameter_values};
