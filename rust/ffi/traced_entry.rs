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
use crate::brdf::eon::EonKernel;
use crate::brdf::ginneken::GinnekenKernel;
use crate::brdf::kernel;
use crate::brdf::lane::LaneKernel;
use crate::brdf::oren_nayar::OrenNayarKernel;
use crate::brdf::real::V3;
use crate::brdf::wolff::WolffKernel;
use crate::brdf::{DiffuseModel, RoughDiffuse};

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
    pub(super) fn table_count(&self) -> usize {
        match &self.bsdf {
            DiffuseModel::Ginneken(_) => 4,
            _ => 0,
        }
    }

    /// van Ginneken's tables in the order the traced kernel gathers them: `I`, `∂I/∂m`,
    /// `μΛ`, `∂(μΛ)/∂m`.
    pub(super) fn table(&self, k: usize) -> &[f32] {
        match &self.bsdf {
            DiffuseModel::Ginneken(g) => {
                let t = g.table();
                match k {
                    0 => t.slope_nodes(),
                    1 => t.slope_derivative_nodes(),
                    2 => t.mu_lambda_nodes(),
                    3 => t.mu_lambda_derivative_nodes(),
                    _ => &[],
                }
            }
            _ => &[],
        }
    }

    /// Tables for per-lane parameters (van Ginneken: the four roughness-axis stacks, built on
    /// first use), registered instead of [`Self::table`]'s when a parameter is textured.
    pub(super) fn lane_table_count(&self) -> usize {
        if self.bsdf.lane_tables().is_some() { 4 } else { 0 }
    }

    pub(super) fn lane_table(&self, k: usize) -> &[f32] {
        self.bsdf.lane_tables().map_or(&[], |t| t.table(k))
    }

    pub(super) fn traced_coefficients(&self, arena: &Arena, params: &[u32], differentiable: bool) -> Vec<u32> {
        let p = |k: usize| params.get(k).map(|&i| Traced::node(arena, i));
        match &self.bsdf {
            DiffuseModel::Lambert(_) => vec![],
            DiffuseModel::OrenNayar(b) => {
                p(0).map_or(vec![], |sigma| ids(arena, OrenNayarKernel::new(sigma, b.model()).coefficients()))
            }
            DiffuseModel::Eon(_) => p(0).map_or(vec![], |r| ids(arena, EonKernel::new(r).coefficients())),
            DiffuseModel::RoughDiffuse(b) => p(0).map_or(vec![], |alpha| {
                ids(
                    arena,
                    OrenNayarKernel::new(RoughDiffuse::sigma_of_alpha(alpha), b.oren_nayar().model()).coefficients(),
                )
            }),
            DiffuseModel::Wolff(b) => match (p(0), p(1)) {
                (Some(int_ior), Some(ext_ior)) => {
                    ids(arena, WolffKernel::new(int_ior / ext_ior, b.normalization()).coefficients())
                }
                _ => vec![],
            },
            // m − m₀: zero in value (the tables were built at the parameter's value m₀), the
            // roughness's gradient in derivative.
            DiffuseModel::Ginneken(b) => match p(0) {
                Some(m) if differentiable => ids(arena, [m - Traced::Lit(b.roughness())]),
                _ => vec![],
            },
        }
    }

    /// The kernel constants for per-lane (textured) parameters, traced: `params` holds every
    /// numeric parameter's value per lane (a texture's `eval_1`, or the constant), in the order
    /// of `numeric_parameters`; the result is in [`Self::traced_coefficients`]' layout, so
    /// [`Self::traced_eval_pdf`] / [`Self::traced_sample`] take it unchanged
    /// (`crate::brdf::lane`). Empty if the model has no per-lane form or `params` is short.
    pub(super) fn traced_lane_coefficients(&self, arena: &Arena, params: &[u32]) -> Vec<u32> {
        let values: Vec<Traced<'_>> = params.iter().map(|&i| Traced::node(arena, i)).collect();
        match self.bsdf.lane_coefficients(&values) {
            Some(c) => c.iter().map(|v| v.id(arena)).collect(),
            None => vec![],
        }
    }

    /// The kernel with the constants `coefficients` (from [`Self::traced_coefficients`]).
    /// `lane`: the constants come from [`Self::traced_lane_coefficients`] (van Ginneken then
    /// reads the roughness-axis stacks the plugin registered, [`Self::lane_table`]).
    fn traced_kernel<'a>(&self, arena: &'a Arena, coefficients: &[u32], lane: bool) -> Option<TracedKernel<'a>> {
        let table = |id| TracedTable { arena, id };
        match &self.bsdf {
            DiffuseModel::Ginneken(_) if lane => {
                let c: Vec<Traced<'a>> = coefficients.iter().map(|&i| Traced::node(arena, i)).collect();
                self.bsdf.kernel_from_coefficients(&c, || Some([table(0), table(1), table(2), table(3)]))
            }
            DiffuseModel::Ginneken(b) => {
                let roughness_derivative = nodes::<1>(arena, coefficients).map(|[dm]| (table(1), table(3), dm));
                Some(LaneKernel::Ginneken(GinnekenKernel {
                    slope: table(0),
                    mu_lambda: table(2),
                    roughness_derivative,
                    shadowing: b.shadowing(),
                }))
            }
            _ => {
                let c: Vec<Traced<'a>> = coefficients.iter().map(|&i| Traced::node(arena, i)).collect();
                self.bsdf.kernel_from_coefficients(&c, || None)
            }
        }
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
