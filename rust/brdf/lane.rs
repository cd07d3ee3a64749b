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
use super::registry::Registered;
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
/// of another scalar type (the traced plugin: Dr.Jit variables).
impl DiffuseModel {
    /// The tables the kernel reads: the constant-parameter kernel's ([`Registered::tables`]),
    /// or with `lane` the per-lane kernel's ([`Registered::lane_tables`]).
    pub fn kernel_tables(&self, lane: bool) -> Vec<&[f32]> {
        dispatch!(self, m => if lane { m.lane_tables() } else { m.tables() })
    }

    /// The kernel constants for numeric parameter values in `T`:
    /// [`Registered::constant_coefficients`], or with `lane` [`Registered::lane_coefficients`]
    /// (each value clamped into its lane clamp first). `None` if `values` is short.
    pub fn kernel_coefficients<T: Real>(&self, values: &[T], lane: bool, differentiable: bool) -> Option<Vec<T>> {
        dispatch!(self, m => if lane { m.lane_coefficients(values) } else { m.constant_coefficients(values, differentiable) })
    }

    /// The kernel from constants `c` ([`Self::kernel_coefficients`]) and tables in `T`'s table
    /// type ([`Self::kernel_tables`] of the same `lane`). `None` if either is short.
    pub fn kernel_from<'t, T: Real + 't>(
        &'t self,
        c: &[T],
        tables: &[T::Table<'t>],
        lane: bool,
    ) -> Option<LaneKernel<'t, T>> {
        dispatch!(self, m => m.kernel_from(c, tables, lane), lane)
    }

    /// The f32 kernel for per-lane parameter `values`; `None` if `values` is too short.
    pub fn lane_kernel_f32(&self, values: &[f32]) -> Option<LaneKernel<'_, f32>> {
        dispatch!(self, m => {
            let tables: Vec<Nodes<'_>> = m.lane_tables().into_iter().filter_map(Nodes::from_slice).collect();
            m.lane_coefficients(values).and_then(|c| m.kernel_from(&c, &tables, true))
        }, lane)
    }
}
