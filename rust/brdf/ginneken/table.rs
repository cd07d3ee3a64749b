//! The fast path: the slope integral `I(θi, θo, Δφ)` tabulated per roughness and interpolated
//! trilinearly. Only `I` is tabulated; the visibility term `P_ill+vis/(μi μo)` is evaluated in
//! closed form at run time, because its `4.41 φ` azimuth factor and its `max/min(θi, θo)` kink
//! interpolate badly while `I` is smooth: without clamping it is exactly
//! `μi μo E[1/√(1+t²)] + sin θi sin θo cos Δφ · ½E[t²/√(1+t²)]`.
//!
//! Axes (chosen so that `I` is close to linear along each of them):
//! * `x = √(1−μ) / (√(1−μ) + √μ)` for each direction ([`axis_of_cos`]): about uniform in angle
//!   near the normal, crowding towards grazing where forward scattering makes `I` fall off
//!   like a power of μ; one square root, no trig. Measured (m = 0.3, 3000 configurations):
//!   the plain `√(1−μ)` axis needed 128 nodes for the error this one reaches with 80.
//! * `c = cos Δφ` ∈ [−1, 1]: `I` is linear in `c` wherever no facet is clamped.
//!
//! `I(θi, θo, Δφ) = I(θo, θi, Δφ)`, so only `x_i ≤ x_o` is integrated and the rest mirrored.

use super::slope_integral::SlopeIntegrator;
use crate::real::Real;
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock, Weak};

/// Nodes along each direction axis.
pub const U_NODES: usize = 80;
/// Nodes along the `cos Δφ` axis.
pub const C_NODES: usize = 32;
/// Gauss–Legendre nodes per radial piece when building (converged to ~1e-7, see tests).
const BUILD_NODES: usize = 24;

/// Nodes of the slope table: `I` at `[iu_i][iu_o][ic]`, flat in that order.
pub const SLOPE_NODES: usize = U_NODES * U_NODES * C_NODES;

/// Cells of the slope table (node `(i, o, c)` is the low corner of cell `(i, o, c)`).
pub const SLOPE_CELLS: usize = (U_NODES - 1) * (U_NODES - 1) * (C_NODES - 1);
/// Values of the cell-corner table: eight per cell ([`SlopeTable::slope_cells`]).
pub const SLOPE_CELL_VALUES: usize = 8 * SLOPE_CELLS;

/// `I` (or `∂I/∂m`) at the nodes. A fixed size, so that lookups know the length at compile time.
type Grid = [f32; SLOPE_NODES];
/// The same, as each cell's eight corners side by side.
type CellGrid = [f32; SLOPE_CELL_VALUES];

/// Flat index of node `(iu_i, iu_o, ic)`.
const fn node_index(iu_i: usize, iu_o: usize, ic: usize) -> usize {
    (iu_i * U_NODES + iu_o) * C_NODES + ic
}

#[derive(Debug)]
pub struct SlopeTable {
    data: Box<Grid>,
    /// `∂I/∂m` at the same nodes (the traced kernels' roughness gradient).
    d_data: Box<Grid>,
    /// `data` and `d_data` as cell corners ([`Self::slope_cells`]), made on first use.
    cells: OnceLock<Box<CellGrid>>,
    d_cells: OnceLock<Box<CellGrid>>,
}

impl SlopeTable {
    /// Tabulates `I` and `∂I/∂m` for roughness `m` (parallel over rows; ~66k integrals).
    pub fn build(m: f64) -> Self {
        let (n_u, n_c) = (U_NODES, C_NODES);
        let integrator = SlopeIntegrator::new(BUILD_NODES);
        let mu_at = |k: usize| cos_of_axis(k as f64 / (n_u - 1) as f64);
        let rows: Vec<Vec<(f32, f32)>> = (0..n_u)
            .into_par_iter()
            .map(|iu_i| {
                let mut row = vec![(0.0f32, 0.0f32); n_u * n_c];
                for iu_o in iu_i..n_u {
                    for ic in 0..n_c {
                        let c = -1.0 + 2.0 * ic as f64 / (n_c - 1) as f64;
                        let (v, d) =
                            integrator.integral_and_derivative(m, mu_at(iu_i), mu_at(iu_o), c.clamp(-1.0, 1.0).acos());
                        row[iu_o * n_c + ic] = (v as f32, d as f32);
                    }
                }
                row
            })
            .collect();
        let zeros =
            || -> Box<Grid> { vec![0.0f32; SLOPE_NODES].into_boxed_slice().try_into().expect("SLOPE_NODES nodes") };
        let (mut data, mut d_data) = (zeros(), zeros());
        for iu_i in 0..n_u {
            for iu_o in iu_i..n_u {
                for ic in 0..n_c {
                    let (v, d) = rows[iu_i][iu_o * n_c + ic];
                    (data[node_index(iu_i, iu_o, ic)], d_data[node_index(iu_i, iu_o, ic)]) = (v, d);
                    (data[node_index(iu_o, iu_i, ic)], d_data[node_index(iu_o, iu_i, ic)]) = (v, d);
                }
            }
        }
        Self { data, d_data, cells: OnceLock::new(), d_cells: OnceLock::new() }
    }

    /// `I` at the nodes, flat in the order `[iu_i][iu_o][ic]` (what [`lookup_layer_in`]
    /// gathers from, in the stacks over m).
    pub fn slope_nodes(&self) -> &[f32; SLOPE_NODES] {
        &self.data
    }

    /// `∂I/∂m` at the nodes, flat as [`Self::slope_nodes`].
    pub fn slope_derivative_nodes(&self) -> &[f32; SLOPE_NODES] {
        &self.d_data
    }

    /// `I` as cell corners (what [`lookup_in`] gathers from): cell `(i, o, c)`, flat in that
    /// order, holds the eight nodes `(i + a, o + b, c + d)` at `8·cell + 4a + 2b + d`. Eight
    /// times the nodes (6.2 MB), for one packet load per lookup instead of eight scattered ones.
    pub fn slope_cells(&self) -> &[f32; SLOPE_CELL_VALUES] {
        self.cells.get_or_init(|| corners_of(&self.data))
    }

    /// `∂I/∂m` as cell corners, laid out as [`Self::slope_cells`].
    pub fn slope_derivative_cells(&self) -> &[f32; SLOPE_CELL_VALUES] {
        self.d_cells.get_or_init(|| corners_of(&self.d_data))
    }

    /// The table for `m`, shared by every model instance with the same roughness for as
    /// long as one of them lives (scenes give many objects the same material).
    pub fn shared(m: f64) -> Arc<SlopeTable> {
        static CACHE: OnceLock<Mutex<HashMap<u64, Weak<SlopeTable>>>> = OnceLock::new();
        let cache = CACHE.get_or_init(Default::default);
        let key = m.to_bits();
        if let Some(t) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&key).and_then(Weak::upgrade) {
            return t;
        }
        // Built outside the lock: another thread may build the same table meanwhile, which
        // wastes work but is harmless.
        let table = Arc::new(SlopeTable::build(m));
        let mut guard = cache.lock().unwrap_or_else(|e| e.into_inner());
        guard.retain(|_, w| w.strong_count() > 0);
        guard.insert(key, Arc::downgrade(&table));
        table
    }
}

/// A node table rearranged as cell corners ([`SlopeTable::slope_cells`]).
fn corners_of(nodes: &Grid) -> Box<CellGrid> {
    let mut cells = vec![0.0f32; SLOPE_CELL_VALUES];
    for i in 0..U_NODES - 1 {
        for o in 0..U_NODES - 1 {
            for c in 0..C_NODES - 1 {
                let cell = (i * (U_NODES - 1) + o) * (C_NODES - 1) + c;
                for k in 0..8 {
                    cells[8 * cell + k] = nodes[node_index(i + (k >> 2), o + ((k >> 1) & 1), c + (k & 1))];
                }
            }
        }
    }
    cells.into_boxed_slice().try_into().expect("SLOPE_CELL_VALUES values")
}

/// Trilinear interpolation of a [`SlopeTable::slope_cells`]-shaped table at axis coordinates
/// `u_i`, `u_o` ([`axis_of_cos`]) and `c = cos Δφ`, in any [`Real`]: one packet gather of the
/// cell's eight corners.
#[inline(always)]
pub fn lookup_in<T: Real>(cells: T::Table<'_>, u_i: T, u_o: T, c: T) -> T {
    let (cell, fractions) = locate(u_i, u_o, c);
    let index = (cell[0].scale((U_NODES - 1) as f64) + cell[1]).fma(T::c((C_NODES - 1) as f64), cell[2]);
    blend(T::gather8(cells, index), fractions)
}

/// [`lookup_in`] on one layer of a stack of node tables ([`SlopeTable::slope_nodes`]-shaped,
/// eight gathers): `layer_base` is the index of the layer's first node (an integer-valued
/// float).
#[inline(always)]
pub fn lookup_layer_in<T: Real>(table: T::Table<'_>, layer_base: T, u_i: T, u_o: T, c: T) -> T {
    let (cell, fractions) = locate(u_i, u_o, c);
    let base = (cell[0].scale(U_NODES as f64) + cell[1]).fma(T::c(C_NODES as f64), cell[2]) + layer_base;
    let at = |k: usize| {
        let offset = (k >> 2) * U_NODES * C_NODES + ((k >> 1) & 1) * C_NODES + (k & 1);
        T::gather(table, base, offset as u32)
    };
    blend(std::array::from_fn(at), fractions)
}

/// The cell `[i, o, c]` (lower node indices, integer-valued floats) holding the point and the
/// point's fractions `[fi, fo, fc]` in it.
#[inline(always)]
fn locate<T: Real>(u_i: T, u_o: T, c: T) -> ([T; 3], [T; 3]) {
    let (i0, fi) = cell(u_i.scale((U_NODES - 1) as f64), U_NODES);
    let (o0, fo) = cell(u_o.scale((U_NODES - 1) as f64), U_NODES);
    let half = T::c(0.5 * (C_NODES - 1) as f64);
    let (c0, fc) = cell(c.fma(half, half), C_NODES);
    ([i0, o0, c0], [fi, fo, fc])
}

/// The trilinear interpolant of a cell's corners (`corners[4a + 2b + d]` at node
/// `(i + a, o + b, c + d)`), written as their weighted sum: the weights are ready before the
/// (usually cache-missing) loads return, after which only a product and a sum remain (nested
/// lerps would leave three dependent levels).
#[inline(always)]
fn blend<T: Real>(corners: [T; 8], [fi, fo, fc]: [T; 3]) -> T {
    let one = T::c(1.0);
    let (gi, go, gc) = (one - fi, one - fo, one - fc);
    let [v000, v001, v010, v011, v100, v101, v110, v111] = corners;
    let pair = |w: T, a: T, b: T| (w * gc).fma(a, (w * fc) * b);
    let v0 = pair(gi * go, v000, v001) + pair(gi * fo, v010, v011);
    let v1 = pair(fi * go, v100, v101) + pair(fi * fo, v110, v111);
    v0 + v1
}

/// Table coordinate of a direction with cosine `mu`: `x = a/(a+b)`, `a = √(1−μ)`, `b = √μ`.
/// Near the normal `x ≈ a ≈ θ/√2` (uniform in angle); near grazing `μ ≈ (1−x)²`, so the
/// nodes crowd towards the horizon where forward scattering makes `I` fall off like a power
/// of μ. Evaluated as `x = (1 − μ + q)/(1 + 2q)`, `q = ab = √(μ(1−μ))` (multiply `a/(a+b)`
/// above and below by `a+b`): one square root instead of two, all terms ≥ 0 (no cancellation).
#[inline(always)]
pub fn axis_of_cos<T: Real>(mu: T) -> T {
    let mu = mu.clamp_to(0.0, 1.0);
    let one_minus = T::c(1.0) - mu;
    let q = (mu * one_minus).safe_sqrt();
    (one_minus + q) / (T::c(1.0) + q.scale(2.0))
}

/// Inverse of [`axis_of_cos`]: `μ = (1−x)² / ((1−x)² + x²)`.
pub fn cos_of_axis(x: f64) -> f64 {
    let y = 1.0 - x;
    y * y / (y * y + x * x)
}

#[cfg(test)]
impl SlopeTable {
    /// `I` at node `(iu_i, iu_o, ic)`, for tests that re-interpolate the table independently.
    pub(crate) fn node(&self, iu_i: usize, iu_o: usize, ic: usize) -> f32 {
        self.data[node_index(iu_i, iu_o, ic)]
    }
}

/// Lower node index (as an integer-valued float) and fraction for the position
/// `s ∈ [0, n−1]` (in node units) on a grid of `n` nodes, clamped so that `index + 1` is valid;
/// NaN maps to 0. The fraction comes from `floor` (no float → int → float round trip).
#[inline(always)]
fn cell<T: Real>(s: T, n: usize) -> (T, T) {
    let last = (n - 2) as f64;
    let s = s.clamp_to(0.0, last + 1.0);
    let lower = s.floor().min(T::c(last));
    (lower, s - lower)
}
