//! van Ginneken with a roughness that varies per lane (a textured `roughness`,
//! `docs/models.md#van-ginneken-with-a-textured-roughness`): the slope tables of
//! [`super::table`] (the 1-D functions and the ratio `r = K/I`) stacked over a roughness axis
//! and interpolated in m as well.
//!
//! Axis: `u = m/(1 + m)`, [`M_NODES`] nodes uniform in u from m = [`M_MIN`] to [`M_MAX`]
//! (denser at small m, where `I` changes fastest relative to m; no logarithm, which the
//! traced scalar lacks). Every node stores both tables and their m-derivatives at fixed
//! directions (the same semi-analytic integrals as the single-roughness tables' `∂/∂m`), so the
//! interpolation in u is **cubic Hermite**: value and slope match at both ends of a cell. Each
//! layer's ratio is looked up on its own node's v axis (`v = m_j s/(m_j s + μ)`), so that every
//! layer is a fixed function of the directions and the interpolant is smooth in m. The value
//! is then accurate to a few 1e-4 between nodes, and its m-derivative (the texture's gradient,
//! exact derivative of the interpolant) is continuous. `μΛ` is evaluated in closed form at the
//! lane's m. Measured against
//! [`super::Ginneken::eval_reference`] by [`super::accuracy::axis_accuracy`] (`tests/kernels/ginneken_fast_path.rs`; docs/models.md).
//!
//! A texture value outside [M_MIN, M_MAX] is clamped into it (NaN gives M_MIN). The stack is
//! built once per process, on first use (M_NODES single-roughness builds, well under a second).

use super::shadowing::{Shadowing, mu_lambda_closed};
use super::table::{
    ONED_NODES, ONED_VALUES, RATIO_AXIS_MAX_M, RATIO_NODES, SlopeGeometry, SlopeTable, oned_cell, oned_in, ratio_layer_in,
};
use super::split::{SlopeSplit, reduced_with, sampler};
use crate::cltc::{ClippedLtc, Sampling};
use crate::kernel::Kernel;
use crate::real::{Nodes, Real, V3};
use std::sync::OnceLock;

/// Smallest and largest roughness on the axis.
pub const M_MIN: f64 = 0.02;
pub const M_MAX: f64 = 4.0;
/// Nodes on the roughness axis.
pub const M_NODES: usize = 13;

/// Values of the stacked 1-D cell tables.
pub const AXIS_ONED_VALUES: usize = M_NODES * ONED_VALUES;
/// Nodes of the stacked ratio tables.
pub const AXIS_RATIO_NODES: usize = M_NODES * RATIO_NODES;
/// `u` of [`RATIO_AXIS_MAX_M`]: layers above it use its v axis, as their tables do
/// ([`super::table::ratio_axis_roughness`]).
const U_RATIO_AXIS_MAX: f64 = RATIO_AXIS_MAX_M / (1.0 + RATIO_AXIS_MAX_M);
/// Packets of eight per layer of the 1-D stacks.
const ONED_PACKETS: usize = ONED_NODES - 1;

fn u_of_m(m: f64) -> f64 {
    m / (1.0 + m)
}

const fn u_min() -> f64 {
    M_MIN / (1.0 + M_MIN)
}

/// Axis spacing in u.
fn du() -> f64 {
    (u_of_m(M_MAX) - u_min()) / (M_NODES - 1) as f64
}

/// Roughness of node `j`.
pub fn m_of_node(j: usize) -> f64 {
    let u = u_min() + j as f64 * du();
    u / (1.0 - u)
}

/// The stacked tables: layer `j` holds node `j`'s 1-D cells ([`SlopeTable::oned_cells`]) and
/// ratio nodes ([`SlopeTable::ratio_nodes`]) and, in the derivative stacks,
/// `Δu · dm/du · ∂/∂m` of each (Hermite's scaled slopes; `dm/du = (1+m)²`).
pub struct RoughnessAxisTables {
    pub oned: Box<[f32; AXIS_ONED_VALUES]>,
    pub ratio: Box<[f32; AXIS_RATIO_NODES]>,
    pub d_oned: Box<[f32; AXIS_ONED_VALUES]>,
    pub d_ratio: Box<[f32; AXIS_RATIO_NODES]>,
}

impl RoughnessAxisTables {
    pub fn build() -> Self {
        fn boxed<const N: usize>(v: Vec<f32>) -> Box<[f32; N]> {
            v.into_boxed_slice().try_into().expect("stack size")
        }
        let (mut oned, mut d_oned) = (Vec::with_capacity(AXIS_ONED_VALUES), Vec::with_capacity(AXIS_ONED_VALUES));
        let (mut ratio, mut d_ratio) = (Vec::with_capacity(AXIS_RATIO_NODES), Vec::with_capacity(AXIS_RATIO_NODES));
        for j in 0..M_NODES {
            let m = m_of_node(j);
            let scale = du() * (1.0 + m) * (1.0 + m);
            let t = SlopeTable::build(m);
            oned.extend_from_slice(t.oned_cells());
            ratio.extend_from_slice(t.ratio_nodes());
            d_oned.extend(t.oned_derivative_cells().iter().map(|&d| (d as f64 * scale) as f32));
            d_ratio.extend(t.ratio_derivative_nodes().iter().map(|&d| (d as f64 * scale) as f32));
        }
        Self { oned: boxed(oned), ratio: boxed(ratio), d_oned: boxed(d_oned), d_ratio: boxed(d_ratio) }
    }

    /// The process's tables, built on first use.
    pub fn shared() -> &'static RoughnessAxisTables {
        static TABLES: OnceLock<RoughnessAxisTables> = OnceLock::new();
        TABLES.get_or_init(RoughnessAxisTables::build)
    }

    /// The four stacks in the order the traced kernel registers them: 1-D functions, ratio,
    /// and the scaled derivative of each.
    pub fn table(&self, k: usize) -> &[f32] {
        match k {
            0 => &self.oned[..],
            1 => &self.ratio[..],
            2 => &self.d_oned[..],
            3 => &self.d_ratio[..],
            _ => &[],
        }
    }

    /// The four stacks as CPU tables, in [`Self::table`]'s order.
    pub fn nodes(&'static self) -> [Nodes<'static>; 4] {
        [Nodes::new(&self.oned), Nodes::new(&self.ratio), Nodes::new(&self.d_oned), Nodes::new(&self.d_ratio)]
    }
}

/// `m` clamped into [M_MIN, M_MAX] (NaN gives M_MIN).
#[inline(always)]
pub fn clamp_roughness<T: Real>(m: T) -> T {
    m.clamp_to(M_MIN, M_MAX)
}

/// van Ginneken at one roughness per lane: the stacked tables, the lane's layer and Hermite
/// weights, and the lane's roughness (for `μΛ`).
#[derive(Clone, Copy)]
pub struct GinnekenAxisKernel<'t, T: Real> {
    /// 1-D functions, ratio, their scaled `∂/∂m` (see [`RoughnessAxisTables`]).
    tables: [T::Table<'t>; 4],
    /// Index of the lower layer (an integer-valued float).
    layer: T,
    /// The lower and upper layers' ratio-table v axes, `[1/m, 1 − 1/m]` of their roughness
    /// (at most [`RATIO_AXIS_MAX_M`]; [`super::table::v_axis`]).
    ratio_axes: [[T; 2]; 2],
    /// The clamped roughness (for μΛ).
    m: T,
    /// Hermite basis `h00, h10, h01, h11` at the lane's position in its cell.
    weights: [T; 4],
    shadowing: Shadowing,
    /// The sampler's roughness variable (`super::sampler_roughness` of the clamped m).
    sampler_t: T,
    /// Sample the fitted lobe rather than the cosine.
    cltc: bool,
}

impl<'t, T: Real> GinnekenAxisKernel<'t, T> {
    /// The kernel at roughness `m` (clamped into the axis), with the stacks `tables`.
    #[inline(always)]
    pub fn new(tables: [T::Table<'t>; 4], m: T, shadowing: Shadowing) -> Self {
        let one = T::c(1.0);
        let m = clamp_roughness(m);
        let u = m / (m + one);
        let last = (M_NODES - 2) as f64;
        let p = ((u - T::c(u_min())).scale(1.0 / du())).clamp_to(0.0, last + 1.0);
        let j = p.floor().min(T::c(last));
        let s = p - j;
        let (s2, one_minus) = (s * s, one - s);
        let weights = [
            (one + s.scale(2.0)) * one_minus * one_minus,
            s * one_minus * one_minus,
            s2 * (T::c(3.0) - s.scale(2.0)),
            s2 * (s - one),
        ];
        let u_lower = j.fma(T::c(du()), T::c(u_min()));
        // 1/m = (1 − u)/u of a layer's capped u.
        let axis = |u: T| {
            let u = u.min(T::c(U_RATIO_AXIS_MAX));
            let inverse = (one - u) / u;
            [inverse, one - inverse]
        };
        Self {
            tables,
            layer: j,
            ratio_axes: [axis(u_lower), axis(u_lower + T::c(du()))],
            m,
            weights,
            shadowing,
            sampler_t: u.scale(1.25),
            cltc: false,
        }
    }

    /// The same kernel sampling the fitted lobe (`Sampling::Cltc`) or the cosine.
    pub fn with_sampling(self, sampling: Sampling) -> Self {
        Self { cltc: sampling == Sampling::Cltc, ..self }
    }

}

/// The split `I = rest / (1 − r)`, each tabulated function the Hermite combination of the
/// lower and upper layers' values and slopes; μΛ in closed form at the lane's m.
impl<'t, T: Real> SlopeSplit<T> for GinnekenAxisKernel<'t, T> {
    #[inline(always)]
    fn directions(&self, g: &SlopeGeometry<T>) -> [([T; 3], T); 2] {
        let [oned, _, d_oned, _] = self.tables;
        // The 1-D functions: the same cell in every layer.
        let oned_base = self.layer.scale(ONED_PACKETS as f64);
        let upper_oned = oned_base + T::c(ONED_PACKETS as f64);
        std::array::from_fn(|k| {
            let c = oned_cell(g.x[k]);
            let (a, da): ([T; 3], [T; 3]) = (oned_in(oned, oned_base, c), oned_in(d_oned, oned_base, c));
            let (b, db): ([T; 3], [T; 3]) = (oned_in(oned, upper_oned, c), oned_in(d_oned, upper_oned, c));
            let f = std::array::from_fn(|j| self.hermite(a[j], da[j], b[j], db[j]));
            (f, mu_lambda_closed(g.mu[k], g.sin[k], self.m))
        })
    }

    #[inline(always)]
    fn ratio(&self, g: &SlopeGeometry<T>) -> T {
        let [_, ratio, _, d_ratio] = self.tables;
        // Each layer on its own v axis.
        let ratio_base = self.layer.scale(RATIO_NODES as f64);
        let layer = |axis: [T; 2], base: T| {
            let [v_i, v_o] = g.v(axis);
            (ratio_layer_in(ratio, base, v_i, v_o, g.phi), ratio_layer_in(d_ratio, base, v_i, v_o, g.phi))
        };
        let (a, da) = layer(self.ratio_axes[0], ratio_base);
        let (b, db) = layer(self.ratio_axes[1], ratio_base + T::c(RATIO_NODES as f64));
        self.hermite(a, da, b, db)
    }
}

impl<'t, T: Real> GinnekenAxisKernel<'t, T> {
    /// The cubic Hermite combination of a function's values `a`, `b` and scaled slopes `da`,
    /// `db` at the lower and upper layers.
    #[inline(always)]
    fn hermite(&self, a: T, da: T, b: T, db: T) -> T {
        let [h00, h10, h01, h11] = self.weights;
        h00.fma(a, h10 * da) + h01.fma(b, h11 * db)
    }
}

impl<'t, T: Real> Kernel<T> for GinnekenAxisKernel<'t, T> {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        reduced_with(self.shadowing, wi, wo, rho, self)
    }

    #[inline(always)]
    fn fitted_sampler(&self) -> Option<impl Fn(T) -> ClippedLtc<T>> {
        self.cltc.then_some(move |mu| sampler(mu, self.sampler_t))
    }
}
