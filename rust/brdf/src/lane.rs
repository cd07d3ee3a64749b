//! Kernels whose parameters vary per lane: a model's numeric parameters given as values of
//! the scalar type (a texture's value at the hit), not fixed at construction
//! (`docs/models.md#spatially-varying-parameters`). The constants are computed from them on
//! every call by the model's own constructors ([`Registered::lane_coefficients`]): in f32 by
//! the Rust renderer and the scalar plugin variants, traced (so per lane, with the texture's
//! gradient) by the JIT variants.
//!
//! Values come in the order of the model's numeric parameters ([`ModelSpec::numeric`]) and are
//! clamped into each parameter's lane clamp ([`ParamSpec::lane_clamp`]), since a texture is
//! not validated as a number is; NaN maps to the lower bound (`Real::max`).
//!
//! [`ModelSpec::numeric`]: super::registry::ModelSpec::numeric
//! [`ParamSpec::lane_clamp`]: super::registry::ParamSpec::lane_clamp

use super::real::{Nodes, Real};
use super::registry::{Evaluation, Flat, Gradients, Registered};
use super::{DiffuseModel, LaneKernel, dispatch};

/// The numeric parameters of the model `kind` (a plugin name), in the order per-lane values
/// are given: the parameters a texture may give. Empty for unknown kinds.
pub fn numeric_parameter_names(kind: &str) -> Vec<&'static str> {
    super::spec(kind).map_or(Vec::new(), |s| s.numeric().map(|p| p.name).collect())
}

/// The number a textured parameter stands for when its model is built (and validated as a
/// number): the texture's `mean` clamped into the range its per-lane values are clamped to,
/// so that any texture is accepted, as its values are per lane. `number(name)` gives another
/// parameter's value when it is a number (Wolff's indices bound each other: int ≥ ext).
pub fn textured_placeholder(kind: &str, name: &str, mean: f64, number: impl Fn(&str) -> Option<f64>) -> f64 {
    super::placeholder(kind, name, mean, &number)
}

/// The model-generic steps from parameter values to a kernel, for front ends that hold values
/// of another scalar type (the traced plugin: Dr.Jit variables). The boundary where a model's
/// named parameters and constants ([`Registered::Parameters`], [`Registered::Coefficients`])
/// become flat slices ([`Flat`]), in the order of their declaration.
impl DiffuseModel {
    /// The tables the kernel reads ([`Registered::tables`]).
    pub fn kernel_tables(&self, evaluation: Evaluation) -> Vec<&[f32]> {
        dispatch!(self, m => m.tables(evaluation))
    }

    /// The kernel constants for numeric parameter values in `T`:
    /// [`Registered::constant_coefficients`], or for [`Evaluation::Lane`]
    /// [`Registered::lane_coefficients`] (each value clamped into its lane clamp first).
    /// `None` if `values` is short.
    pub fn kernel_coefficients<T: Real>(
        &self,
        values: &[T],
        evaluation: Evaluation,
        gradients: Gradients,
    ) -> Option<Vec<T>> {
        dispatch!(self, m => {
            let p = Flat::from_flat(values)?;
            let c = match evaluation {
                Evaluation::Constant => m.constant_coefficients::<T>(p, gradients),
                Evaluation::Lane => m.lane_coefficients::<T>(p),
            };
            Some(c.to_flat())
        })
    }

    /// The kernel from constants `c` ([`Self::kernel_coefficients`]) and tables in `T`'s table
    /// type ([`Self::kernel_tables`] of the same `evaluation`). `None` if either is short.
    pub fn kernel_from<'t, T: Real + 't>(
        &'t self,
        c: &[T],
        tables: &[T::Table<'t>],
        evaluation: Evaluation,
    ) -> Option<LaneKernel<'t, T>> {
        dispatch!(self, m => m.kernel_from::<T>(Flat::from_flat(c)?, tables, evaluation), lane)
    }

    /// The f32 kernel for per-lane parameter `values`; `None` if `values` is too short.
    pub fn lane_kernel_f32(&self, values: &[f32]) -> Option<LaneKernel<'_, f32>> {
        dispatch!(self, m => {
            let tables: Vec<Nodes<'_>> =
                m.tables(Evaluation::Lane).into_iter().filter_map(Nodes::from_slice).collect();
            m.kernel_from::<f32>(m.lane_coefficients::<f32>(Flat::from_flat(values)?), &tables, Evaluation::Lane)
        }, lane)
    }
}
