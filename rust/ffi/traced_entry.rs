//! The traced entry points (Mitsuba's JIT variants): the same generic kernels as the CPU
//! (`crate::brdf::kernel`), run with [`Traced`] values, so every operation is recorded into
//! Dr.Jit on the C++ side. Two steps per parameter value and per call:
//! 1. [`Model::traced_coefficients`] turns the numeric parameters (traced, possibly with
//!    gradients) into the kernel's constants, once per `parameters_changed`;
//! 2. [`Model::traced_eval_pdf`] / [`Model::traced_sample`] rebuild the kernel from those
//!    constants and evaluate it on the call's directions and reflectance.
//!
//! Slices of unexpected lengths (a bug in the C++ caller) give zeros, never a panic.

use super::Model;
use super::bridge::ffi::Arena;
use super::traced::{Traced, TracedTable};
use crate::brdf::kernel;
use crate::brdf::real::V3;
use crate::brdf::registry::Registered;
use crate::brdf::{LaneKernel, dispatch};

/// One model's kernel with traced constants.
type TracedKernel<'a> = LaneKernel<'a, Traced<'a>>;

/// The first `N` indices of `ids` as traced values, or `None` if there are fewer.
fn nodes<'a, const N: usize>(arena: &'a Arena, ids: &[u32]) -> Option<[Traced<'a>; N]> {
    let ids: &[u32; N] = ids.get(..N)?.try_into().ok()?;
    Some(ids.map(|i| Traced::node(arena, i)))
}

fn ids<const N: usize>(arena: &Arena, values: [Traced<'_>; N]) -> Vec<u32> {
    values.iter().map(|v| v.id(arena)).collect()
}

/// Calls `$f::<N>` with the channel count `$n` (Mitsuba's mono, RGB and spectral variants)
/// turned into a const generic; other counts give `$otherwise`.
macro_rules! by_channels {
    ($n:expr, $f:ident, $otherwise:expr) => {
        match $n {
            1 => $f::<1>,
            3 => $f::<3>,
            4 => $f::<4>,
            _ => return $otherwise,
        }
    };
}

impl Model {
    /// The number of tables the constant-parameter kernel reads ([`Registered::tables`]).
    pub(super) fn table_count(&self) -> usize {
        dispatch!(&self.bsdf, m => m.tables().len())
    }

    /// Table `k` in the order the traced kernel gathers them (van Ginneken: `I`, `∂I/∂m`,
    /// `μΛ`, `∂(μΛ)/∂m`); empty past the end.
    pub(super) fn table(&self, k: usize) -> &[f32] {
        dispatch!(&self.bsdf, m => m.tables().get(k).copied().unwrap_or(&[]))
    }

    /// Tables for per-lane parameters ([`Registered::lane_tables`]: van Ginneken's four
    /// roughness-axis stacks, built on first use), registered instead of [`Self::table`]'s
    /// when a parameter is textured.
    pub(super) fn lane_table_count(&self) -> usize {
        dispatch!(&self.bsdf, m => m.lane_tables().len())
    }

    pub(super) fn lane_table(&self, k: usize) -> &[f32] {
        dispatch!(&self.bsdf, m => m.lane_tables().get(k).copied().unwrap_or(&[]))
    }

    /// The kernel constants for the numeric parameters `params` (traced, possibly with
    /// gradients), once per `parameters_changed` ([`Registered::constant_coefficients`]).
    /// Empty if `params` is short.
    pub(super) fn traced_coefficients(&self, arena: &Arena, params: &[u32], differentiable: bool) -> Vec<u32> {
        let values: Vec<Traced<'_>> = params.iter().map(|&i| Traced::node(arena, i)).collect();
        let c = dispatch!(&self.bsdf, m => m.constant_coefficients(&values, differentiable));
        c.map_or(vec![], |c| c.iter().map(|v| v.id(arena)).collect())
    }

    /// The kernel constants for per-lane (textured) parameters, traced: `params` holds every
    /// numeric parameter's value per lane (a texture's `eval_1`, or the constant), in the order
    /// of `numeric_parameters`; the result goes to [`Self::traced_eval_pdf`] /
    /// [`Self::traced_sample`] with `lane` set (`crate::brdf::lane`). Empty if `params` is short.
    pub(super) fn traced_lane_coefficients(&self, arena: &Arena, params: &[u32]) -> Vec<u32> {
        let values: Vec<Traced<'_>> = params.iter().map(|&i| Traced::node(arena, i)).collect();
        let c = dispatch!(&self.bsdf, m => m.lane_coefficients(&values));
        c.map_or(vec![], |c| c.iter().map(|v| v.id(arena)).collect())
    }

    /// The kernel with the constants `coefficients` and the registered tables (those of
    /// [`Self::lane_table`] when `lane`, else [`Self::table`]'s).
    fn traced_kernel<'a>(&self, arena: &'a Arena, coefficients: &[u32], lane: bool) -> Option<TracedKernel<'a>> {
        let c: Vec<Traced<'a>> = coefficients.iter().map(|&i| Traced::node(arena, i)).collect();
        let count = if lane { self.lane_table_count() } else { self.table_count() };
        let tables: Vec<TracedTable<'a>> = (0..count as u32).map(|id| TracedTable { arena, id }).collect();
        dispatch!(&self.bsdf, m => m.kernel_from(&c, &tables, lane), lane)
    }

    #[allow(clippy::too_many_arguments)] // the bridge's shape: arena, constants, inputs, outputs
    pub(super) fn traced_eval_pdf(
        &self,
        arena: &Arena,
        coefficients: &[u32],
        lane: bool,
        wi: &[u32],
        wo: &[u32],
        rho: &[u32],
        value: &mut [u32],
    ) -> u32 {
        #[allow(clippy::too_many_arguments)]
        fn go<const N: usize>(
            m: &Model,
            arena: &Arena,
            coefficients: &[u32],
            lane: bool,
            wi: &[u32],
            wo: &[u32],
            rho: &[u32],
            value: &mut [u32],
        ) -> Option<u32> {
            let k = m.traced_kernel(arena, coefficients, lane)?;
            let ([wx, wy, wz], [ox, oy, oz]) = (nodes::<3>(arena, wi)?, nodes::<3>(arena, wo)?);
            let (v, pdf) = kernel::eval_cos_pdf(&k, V3::new(wx, wy, wz), V3::new(ox, oy, oz), nodes::<N>(arena, rho)?);
            value.get_mut(..N)?.copy_from_slice(&ids(arena, v));
            Some(pdf.id(arena))
        }
        let zero = || arena.lit(0.0);
        by_channels!(rho.len(), go, zero())(self, arena, coefficients, lane, wi, wo, rho, value).unwrap_or_else(zero)
    }

    #[allow(clippy::too_many_arguments)] // the bridge's shape: arena, constants, inputs, outputs
    pub(super) fn traced_sample(
        &self,
        arena: &Arena,
        coefficients: &[u32],
        lane: bool,
        wi: &[u32],
        u1: u32,
        u2: u32,
        rho: &[u32],
        wo: &mut [u32],
        weight: &mut [u32],
    ) -> u32 {
        #[allow(clippy::too_many_arguments)]
        fn go<const N: usize>(
            m: &Model,
            arena: &Arena,
            coefficients: &[u32],
            lane: bool,
            wi: &[u32],
            u: [u32; 2],
            rho: &[u32],
            wo: &mut [u32],
            weight: &mut [u32],
        ) -> Option<u32> {
            let k = m.traced_kernel(arena, coefficients, lane)?;
            let [wx, wy, wz] = nodes::<3>(arena, wi)?;
            let [u1, u2] = u.map(|i| Traced::node(arena, i));
            let (d, w, pdf) = kernel::sample(&k, V3::new(wx, wy, wz), u1, u2, nodes::<N>(arena, rho)?);
            wo.get_mut(..3)?.copy_from_slice(&ids(arena, [d.x, d.y, d.z]));
            weight.get_mut(..N)?.copy_from_slice(&ids(arena, w));
            Some(pdf.id(arena))
        }
        let zero = || arena.lit(0.0);
        by_channels!(rho.len(), go, zero())(self, arena, coefficients, lane, wi, [u1, u2], rho, wo, weight)
            .unwrap_or_else(zero)
    }
}
