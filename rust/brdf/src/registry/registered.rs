//! What a model implements to be registered ([`Registered`]): its SPEC, how it is built from
//! its parameters, and how its kernel is made from constants in any [`Real`].

use super::brdf::KernelBrdf;
use super::flat::Flat;
use super::spec::ModelSpec;
use super::values::Values;
use crate::kernel::Kernel;
use crate::params::{ParamError, ParamValue};
use crate::real::Real;
use std::fmt::Debug;

/// Which kernel the constants are for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evaluation {
    /// The model's own parameter values, fixed for the call (van Ginneken: the tables of its
    /// roughness, [`Registered::tables`]).
    Constant,
    /// Parameters that vary per lane (textures, `docs/models.md#spatially-varying-parameters`;
    /// van Ginneken: the tables stacked over the roughness).
    Lane,
}

/// Whether the numeric parameters carry gradients the constants must keep (the traced
/// plugin's differentiable parameters).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gradients {
    Needed,
    NotNeeded,
}

/// What a model implements to be registered; everything else about it is derived. `T` in the
/// kernel methods is any [`Real`]: f32 and f64 on the CPU, `F32x8`, and the plugin's traced
/// Dr.Jit values (`matte_plugin::traced`), so one implementation serves all of them.
pub trait Registered: KernelBrdf + Clone + Debug + PartialEq + Sized + 'static {
    const SPEC: ModelSpec;

    /// The model's kernel with its constants in `T`, built by [`Self::kernel_from`].
    type Lane<'t, T: Real + 't>: Kernel<T> + Copy;

    /// The model from its parameters (defaults filled in, ranges checked). Checks that
    /// involve several parameters (Wolff: int_ior ≥ ext_ior) are made here.
    fn build(values: &Values) -> Result<Self, ParamError>;

    /// The effective value of every parameter, in the SPEC's order (numbers as the model
    /// stores them, words and flags as text): [`parameter_values!`].
    fn values(&self) -> Vec<ParamValue>;

    /// The numeric parameters by name ([`flat_values!`], or [`NoValues`]), in the order of
    /// [`ModelSpec::numeric`] (checked at compile time): the values a texture or the traced
    /// plugin gives.
    type Parameters<T: Real>: Flat<T>;

    /// The kernel's constants by name ([`flat_values!`], or [`NoValues`]).
    type Coefficients<T: Real>: Flat<T>;

    /// The kernel constants for numeric parameter values in `T`, as the traced plugin computes
    /// them once per parameter change (with the parameters' gradients if `gradients` says so).
    fn constant_coefficients<T: Real>(&self, p: Self::Parameters<T>, gradients: Gradients) -> Self::Coefficients<T>;

    /// The kernel constants for per-lane (textured) values, each clamped into its lane clamp
    /// first (`docs/models.md#spatially-varying-parameters`). Default: clamp, then
    /// [`Self::constant_coefficients`] with gradients.
    #[inline(always)]
    fn lane_coefficients<T: Real>(&self, p: Self::Parameters<T>) -> Self::Coefficients<T> {
        self.constant_coefficients(clamp_lanes::<Self, T>(p), Gradients::Needed)
    }

    /// The kernel from constants `c` (of either coefficient method) and the tables
    /// ([`Self::tables`] of the same `evaluation`) in `T`'s table type. `None` if `tables` is
    /// short.
    fn kernel_from<'t, T: Real + 't>(
        &'t self,
        c: Self::Coefficients<T>,
        tables: &[T::Table<'t>],
        evaluation: Evaluation,
    ) -> Option<Self::Lane<'t, T>>;

    /// Tables the kernel reads (van Ginneken's slope integral and its derivative at its
    /// roughness, or for [`Evaluation::Lane`] stacked over the roughness; `tabulated_brdf`'s
    /// values); the plugin registers them as Dr.Jit arrays.
    fn tables(&self, evaluation: Evaluation) -> Vec<&[f32]> {
        let _ = evaluation;
        Vec::new()
    }

    /// The number a textured parameter `name` stands for when the model is built and
    /// validated as a number: the texture's `mean` clamped into the lane clamp. `number`
    /// gives another parameter's value when it is a number (Wolff's indices bound each other).
    fn placeholder(name: &str, mean: f64, number: &dyn Fn(&str) -> Option<f64>) -> f64 {
        let _ = number;
        Self::SPEC.param(name).map_or(mean, |p| p.clamp_lane(mean))
    }
}

/// The numeric parameters `p` of model `M`, each clamped into its lane clamp (NaN to the
/// lower bound).
#[inline(always)]
pub fn clamp_lanes<M: Registered, T: Real>(p: M::Parameters<T>) -> M::Parameters<T> {
    p.map(|k, x| {
        let Some(spec) = M::SPEC.numeric().nth(k) else { return x };
        let (lo, hi) = spec.lane_clamp;
        let x = if lo > f64::NEG_INFINITY { x.max(T::c(lo)) } else { x };
        if hi < f64::INFINITY { x.min(T::c(hi)) } else { x }
    })
}
