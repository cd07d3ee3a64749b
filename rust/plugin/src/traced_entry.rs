//! The traced entry points (Mitsuba's JIT variants): the same generic kernels as the CPU
//! (`matte_brdf::kernel`), run with [`Traced`] values, so every operation is recorded into
//! Dr.Jit on the C++ side. Two steps per parameter value and per call:
//! 1. [`PluginBsdf::traced_coefficients`] turns the numeric parameters (traced, possibly with
//!    gradients) into the kernel's constants, once per `parameters_changed`;
//! 2. [`PluginBsdf::traced_eval_pdf`] / [`PluginBsdf::traced_sample`] rebuild the kernel from those
//!    constants and evaluate it on the call's directions and reflectance.
//!
//! Slices of unexpected lengths (a bug in the C++ caller) give zeros, never a panic.

use super::bridge::ffi::Arena;
use super::plugin_bsdf::PluginBsdf;
use super::traced::{Traced, TracedTable};
use matte_brdf::LaneKernel;
use matte_brdf::kernel;
use matte_brdf::real::V3;
use matte_brdf::registry::{Evaluation, Gradients};

/// The bridge's `lane` flag (the C++ side's: a numeric parameter is textured).
fn evaluation(lane: bool) -> Evaluation {
    if lane { Evaluation::Lane } else { Evaluation::Constant }
}

/// The first `N` indices of `ids` as traced values, or `None` if there are fewer.
fn nodes<'a, const N: usize>(arena: &'a Arena, ids: &[u32]) -> Option<[Traced<'a>; N]> {
    let ids: &[u32; N] = ids.get(..N)?.try_into().ok()?;
    Some(ids.map(|i| Traced::node(arena, i)))
}

fn ids<const N: usize>(arena: &Arena, values: [Traced<'_>; N]) -> Vec<u32> {
    values.iter().map(|v| v.id(arena)).collect()
}

/// Evaluates `$body` with the constant `$N` set to the channel count `$n` (Mitsuba's mono,
/// RGB and spectral variants: 1, 3, 4), so that `$body` can use it as a const generic; other
/// counts give `None`.
macro_rules! with_channels {
    ($n:expr, $N:ident => $body:expr) => {
        match $n {
            1 => {
                const $N: usize = 1;
                $body
            }
            3 => {
                const $N: usize = 3;
                $body
            }
            4 => {
                const $N: usize = 4;
                $body
            }
            _ => None,
        }
    };
}

impl PluginBsdf {
    /// The number of tables the kernel reads ([`Registered::tables`]: with `lane`, van
    /// Ginneken's roughness-axis stacks, built on first use).
    ///
    /// [`Registered::tables`]: matte_brdf::registry::Registered::tables
    pub(super) fn table_count(&self, lane: bool) -> usize {
        self.model.kernel_tables(evaluation(lane)).len()
    }

    /// Table `k` in the order the traced kernel gathers them (van Ginneken: `I`, `∂I/∂m`,
    /// `μΛ`, `∂(μΛ)/∂m`; `tabulated_brdf`: its values); empty past the end.
    pub(super) fn table(&self, k: usize, lane: bool) -> &[f32] {
        self.model.kernel_tables(evaluation(lane)).get(k).copied().unwrap_or(&[])
    }

    /// The kernel constants for the numeric parameters `params` (traced, in the order of
    /// `numeric_parameters`): [`Registered::constant_coefficients`], once per
    /// `parameters_changed`; with `lane`, [`Registered::lane_coefficients`] of the values at
    /// the call's lanes (textures, clamped into range). Empty if `params` is short.
    ///
    /// [`Registered::constant_coefficients`]: matte_brdf::registry::Registered::constant_coefficients
    /// [`Registered::lane_coefficients`]: matte_brdf::registry::Registered::lane_coefficients
    pub(super) fn traced_coefficients(
        &self,
        arena: &Arena,
        params: &[u32],
        lane: bool,
        differentiable: bool,
    ) -> Vec<u32> {
        let values: Vec<Traced<'_>> = params.iter().map(|&i| Traced::node(arena, i)).collect();
        let gradients = if differentiable { Gradients::Needed } else { Gradients::NotNeeded };
        let c = self.model.kernel_coefficients(&values, evaluation(lane), gradients);
        c.map_or(vec![], |c| c.iter().map(|v| v.id(arena)).collect())
    }

    /// The kernel with the constants `coefficients` and the registered tables
    /// ([`Self::table`] of the same `lane`).
    fn traced_kernel<'m, 'a: 'm>(
        &'m self,
        arena: &'a Arena,
        coefficients: &[u32],
        lane: bool,
    ) -> Option<LaneKernel<'m, Traced<'a>>> {
        let c: Vec<Traced<'a>> = coefficients.iter().map(|&i| Traced::node(arena, i)).collect();
        let tables: Vec<TracedTable<'a>> =
            (0..self.table_count(lane) as u32).map(|id| TracedTable { arena, id }).collect();
        self.model.kernel_from(&c, &tables, evaluation(lane))
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
        let pdf = with_channels!(rho.len(), N => (|| {
            let k = self.traced_kernel(arena, coefficients, lane)?;
            let ([wx, wy, wz], [ox, oy, oz]) = (nodes::<3>(arena, wi)?, nodes::<3>(arena, wo)?);
            let (v, pdf) = kernel::eval_cos_pdf(&k, V3::new(wx, wy, wz), V3::new(ox, oy, oz), nodes::<N>(arena, rho)?);
            value.get_mut(..N)?.copy_from_slice(&ids(arena, v));
            Some(pdf.id(arena))
        })());
        pdf.unwrap_or_else(|| arena.lit(0.0))
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
        let pdf = with_channels!(rho.len(), N => (|| {
            let k = self.traced_kernel(arena, coefficients, lane)?;
            let [wx, wy, wz] = nodes::<3>(arena, wi)?;
            let (u1, u2) = (Traced::node(arena, u1), Traced::node(arena, u2));
            let (d, w, pdf) = kernel::sample(&k, V3::new(wx, wy, wz), u1, u2, nodes::<N>(arena, rho)?);
            wo.get_mut(..3)?.copy_from_slice(&ids(arena, [d.x, d.y, d.z]));
            weight.get_mut(..N)?.copy_from_slice(&ids(arena, w));
            Some(pdf.id(arena))
        })());
        pdf.unwrap_or_else(|| arena.lit(0.0))
    }
}
