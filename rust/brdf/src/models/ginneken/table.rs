//! The fast path: the slope integral `I(θi, θo, Δφ)` per roughness, split as
//! `I = rest / (1 − r)` (derivation and measurements in
//! `validation/experiments/slope_fit_results.md`, cross-checked by
//! `validation/experiments/fit_slope_integral.py`), and Smith's `μΛ` of each direction for the
//! visibility term `P_ill+vis/(μi μo)`, whose azimuth factor is evaluated at run time.
//!
//! * `rest = μo P0(θi) + μi P0(θo) + so P1(θi) + si P1(θo) + (1 + cos Δφ) si so (H(θi) + H(θo))`
//!   is a sum of non-negative terms (no cancellation) built from three 1-D functions of one
//!   direction ([`SlopeIntegrator::direction_functions`]). They are tabulated as
//!   `[P0/μ², P1/μ³, H/μ]` (smooth, finite and non-zero on μ ∈ [0, 1]), with μΛ, on
//!   [`ONED_NODES`] nodes of the axis `x = sin θ/(sin θ + μ)` ([`axis_of_cos`]: about uniform
//!   in angle near the normal, `1 − x ≈ μ` near grazing), linearly interpolated.
//! * `r = K/I ∈ [0, 1)` is the share of the wedge K of slopes whose facet faces away from both
//!   directions ([`SlopeIntegrator::wedge_integral_and_derivative`]), the only 3-D part: zero
//!   unless both directions are grazing and close in azimuth. Tabulated on [`R_NODES`]³ nodes
//!   over `v = m sin θ / (m sin θ + μ) = 1/(1 + cot θ/m)` per direction ([`v_axis`], Smith's
//!   variable mapped to [0, 1]) and Δφ uniform in [0, π], trilinear. As a ratio, its error is
//!   relative to `I`.
//!
//! Per roughness 40 KB of nodes (4 KB of 1-D functions, 31 KB of r), read through cell
//! layouts of 8 KB and 219 KB (one packet gather each) that hold what the interpolation needs:
//! per 1-D cell the lower node and the differences to the upper one, per ratio cell the eight
//! coefficients of its trilinear interpolant. The 6.2 MB trilinear table of `I` that preceded
//! them was less accurate: at m = 0.3, 0.07 % / 0.16 % for θ ≤ 80° / 85° against
//! 0.30 % / 0.44 % (`docs/models.md`). 20³ rather than 16³ nodes for r (17.5 KB, half the
//! error of the old table at m = 0.3) keeps m = 1 within the 0.5 % of
//! `tests/kernels/ginneken_fast_path.rs` (16³: 0.55 %).

use super::shadowing::{d_mu_lambda_dm, mu_lambda};
use super::slope_integral::SlopeIntegrator;
use crate::real::Real;
use rayon::prelude::*;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::sync::{Arc, Mutex, OnceLock, Weak};

/// Nodes of the 1-D functions along [`axis_of_cos`].
pub const ONED_NODES: usize = 256;
/// Values of the 1-D cell table: per cell `[P0/μ², P1/μ³, H/μ, μΛ]` at its lower node, then
/// their differences to the upper node ([`oned_in`] loads them as one packet of eight and
/// interpolates with one FMA each).
pub const ONED_VALUES: usize = 8 * (ONED_NODES - 1);
/// Nodes of the ratio table along each of its three axes `(v_i, v_o, Δφ)`.
pub const R_NODES: usize = 20;
/// Nodes of the ratio table, flat in the order `[iv_i][iv_o][iφ]`.
pub const RATIO_NODES: usize = R_NODES * R_NODES * R_NODES;
/// Values of the ratio table as cells (eight trilinear coefficients per cell,
/// [`SlopeTable::ratio_cells`]).
pub const RATIO_CELL_VALUES: usize = 8 * (R_NODES - 1) * (R_NODES - 1) * (R_NODES - 1);
/// Gauss–Legendre nodes per piece when building (the tables' errors are those of the numpy
/// prototype, which integrates with 32 to 160 nodes, to the digits `matte tables` prints).
const BUILD_NODES: usize = 24;
/// Smallest cosine at which the tables are built (the normalised 1-D functions have finite
/// limits at μ = 0 that the quadrature cannot divide out).
const MIN_BUILD_COS: f64 = 1e-9;

/// Flat index of ratio node `(i, o, p)`.
const fn ratio_index(i: usize, o: usize, p: usize) -> usize {
    (i * R_NODES + o) * R_NODES + p
}

#[derive(Debug)]
pub struct SlopeTable {
    /// `[P0/μ², P1/μ³, H/μ, μΛ]` as cells ([`ONED_VALUES`]).
    oned: Box<[f32; ONED_VALUES]>,
    /// Their `∂/∂m` at fixed μ, laid out alike (the traced kernels' roughness gradient).
    d_oned: Box<[f32; ONED_VALUES]>,
    /// `r = K/I` at the nodes.
    ratio: Box<[f32; RATIO_NODES]>,
    /// `∂r/∂m` at each node's fixed directions, `(∂K − r ∂I)/I`.
    d_ratio: Box<[f32; RATIO_NODES]>,
    /// `ratio` and `d_ratio` as cells of trilinear coefficients.
    ratio_cells: Box<[f32; RATIO_CELL_VALUES]>,
    d_ratio_cells: Box<[f32; RATIO_CELL_VALUES]>,
}

impl SlopeTable {
    /// Tabulates the 1-D functions (128 × 3 integrals), `r` and their `∂/∂m` for roughness `m`
    /// (4,200 pairs of `K`, `I`, by symmetry in the two directions).
    pub fn build(m: f64) -> Self {
        let integrator = SlopeIntegrator::new(BUILD_NODES);
        // Per node: the normalised functions and μΛ, and their ∂/∂m.
        let oned_nodes: Vec<[[f64; 4]; 2]> = (0..ONED_NODES)
            .into_par_iter()
            .map(|k| {
                let mu = cos_of_axis(k as f64 / (ONED_NODES - 1) as f64).clamp(MIN_BUILD_COS, 1.0);
                let (f, d) = integrator.direction_functions(m, mu);
                let scale = [1.0 / (mu * mu), 1.0 / (mu * mu * mu), 1.0 / mu];
                let sin = (1.0 - mu * mu).sqrt();
                let (ml, d_ml) = (mu_lambda(mu, sin, m), d_mu_lambda_dm(mu, sin, m));
                let value = |j: usize| if j < 3 { f[j] * scale[j] } else { ml };
                let derivative = |j: usize| if j < 3 { d[j] * scale[j] } else { d_ml };
                [std::array::from_fn(value), std::array::from_fn(derivative)]
            })
            .collect();
        let cells = |which: usize| -> Box<[f32; ONED_VALUES]> {
            let mut out = vec![0.0f32; ONED_VALUES];
            for k in 0..ONED_NODES - 1 {
                let (lo, hi) = (oned_nodes[k][which], oned_nodes[k + 1][which]);
                for j in 0..4 {
                    (out[8 * k + j], out[8 * k + 4 + j]) = (lo[j] as f32, (hi[j] - lo[j]) as f32);
                }
            }
            out.into_boxed_slice().try_into().expect("ONED_VALUES values")
        };
        let (oned, d_oned) = (cells(0), cells(1));

        let axis_m = ratio_axis_roughness(m);
        let mu_at = |k: usize| cos_of_v(k as f64 / (R_NODES - 1) as f64, axis_m).max(MIN_BUILD_COS);
        let rows: Vec<Vec<(f32, f32)>> = (0..R_NODES)
            .into_par_iter()
            .map(|i| {
                let mut row = vec![(0.0f32, 0.0f32); R_NODES * R_NODES];
                for o in i..R_NODES {
                    for p in 0..R_NODES {
                        let phi = PI * p as f64 / (R_NODES - 1) as f64;
                        let (mi, mo) = (mu_at(i), mu_at(o));
                        let (k, dk) = integrator.wedge_integral_and_derivative(m, mi, mo, phi);
                        let (v, dv) = integrator.integral_and_derivative(m, mi, mo, phi);
                        let r = k / v;
                        row[o * R_NODES + p] = (r as f32, ((dk - r * dv) / v) as f32);
                    }
                }
                row
            })
            .collect();
        let zeros = || -> Box<[f32; RATIO_NODES]> { Box::new([0.0f32; RATIO_NODES]) };
        let (mut ratio, mut d_ratio) = (zeros(), zeros());
        for i in 0..R_NODES {
            for o in i..R_NODES {
                for p in 0..R_NODES {
                    let (r, d) = rows[i][o * R_NODES + p];
                    (ratio[ratio_index(i, o, p)], d_ratio[ratio_index(i, o, p)]) = (r, d);
                    (ratio[ratio_index(o, i, p)], d_ratio[ratio_index(o, i, p)]) = (r, d);
                }
            }
        }
        let (ratio_cells, d_ratio_cells) = (coefficient_cells(&ratio), coefficient_cells(&d_ratio));
        Self { oned, d_oned, ratio, d_ratio, ratio_cells, d_ratio_cells }
    }

    /// `[P0/μ², P1/μ³, H/μ, μΛ]` as cells (what [`oned_in`] gathers from).
    pub fn oned_cells(&self) -> &[f32; ONED_VALUES] {
        &self.oned
    }

    /// Their `∂/∂m`, laid out as [`Self::oned_cells`].
    pub fn oned_derivative_cells(&self) -> &[f32; ONED_VALUES] {
        &self.d_oned
    }

    /// `r = K/I` at the nodes, flat in the order `[iv_i][iv_o][iφ]` (what
    /// [`ratio_layer_in`] gathers from, in the stacks over m).
    pub fn ratio_nodes(&self) -> &[f32; RATIO_NODES] {
        &self.ratio
    }

    /// `∂r/∂m` at the nodes, flat as [`Self::ratio_nodes`].
    pub fn ratio_derivative_nodes(&self) -> &[f32; RATIO_NODES] {
        &self.d_ratio
    }

    /// `r` as cells (what [`ratio_in`] gathers from): cell `(i, o, p)`, flat in that order,
    /// holds at `8·cell + 4a + 2b + d` the coefficient of `fi^a fo^b fc^d` of its trilinear
    /// interpolant (the fractions in the cell), for one packet load per lookup instead of eight
    /// scattered ones, and seven FMAs (219 KB).
    pub fn ratio_cells(&self) -> &[f32; RATIO_CELL_VALUES] {
        &self.ratio_cells
    }

    /// `∂r/∂m` as cells, laid out as [`Self::ratio_cells`].
    pub fn ratio_derivative_cells(&self) -> &[f32; RATIO_CELL_VALUES] {
        &self.d_ratio_cells
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

#[cfg(test)]
impl SlopeTable {
    /// `[P0/μ², P1/μ³, H/μ, μΛ]` at 1-D node `k`, for tests that re-interpolate independently.
    pub(crate) fn oned_node(&self, k: usize) -> [f32; 4] {
        let cell = k.min(ONED_NODES - 2);
        let upper: f32 = if k < ONED_NODES - 1 { 0.0 } else { 1.0 };
        std::array::from_fn(|j| upper.mul_add(self.oned[8 * cell + 4 + j], self.oned[8 * cell + j]))
    }

    /// `r` at node `(i, o, p)`.
    pub(crate) fn ratio_node(&self, i: usize, o: usize, p: usize) -> f32 {
        self.ratio[ratio_index(i, o, p)]
    }
}

/// A node table rearranged as cells of trilinear coefficients ([`SlopeTable::ratio_cells`]):
/// cell `(i, o, p)` holds at `8·cell + 4a + 2b + d` the coefficient of `fi^a fo^b fc^d`, the
/// mixed finite difference `Δi^a Δo^b Δφ^d` of its corners (computed in f64).
fn coefficient_cells(nodes: &[f32; RATIO_NODES]) -> Box<[f32; RATIO_CELL_VALUES]> {
    let n = R_NODES - 1;
    let mut cells = vec![0.0f32; RATIO_CELL_VALUES];
    for i in 0..n {
        for o in 0..n {
            for p in 0..n {
                let cell = (i * n + o) * n + p;
                let corner = |a: usize, b: usize, d: usize| nodes[ratio_index(i + a, o + b, p + d)] as f64;
                for k in 0..8 {
                    let (a, b, d) = (k >> 2, (k >> 1) & 1, k & 1);
                    // Σ over the corners (a', b', d') ≤ (a, b, d) of ± corner, the sign (−1)^(number of
                    // axes where the corner is at 0 but the coefficient's power is 1).
                    let mut c = 0.0;
                    for a2 in 0..=a {
                        for b2 in 0..=b {
                            for d2 in 0..=d {
                                let sign = if (a - a2 + b - b2 + d - d2) % 2 == 0 { 1.0 } else { -1.0 };
                                c += sign * corner(a2, b2, d2);
                            }
                        }
                    }
                    cells[8 * cell + k] = c as f32;
                }
            }
        }
    }
    cells.into_boxed_slice().try_into().expect("RATIO_CELL_VALUES values")
}

/// What the split needs of one configuration, all of it already computed by the kernel:
/// cosines (clamped), sines, [`axis_of_cos`] coordinates, `si so (1 + cos Δφ)` and `Δφ`.
#[derive(Clone, Copy)]
pub struct SlopeGeometry<T> {
    pub mu: [T; 2],
    pub sin: [T; 2],
    pub x: [T; 2],
    /// `si so (1 + cos Δφ) = si so + s` with `s = wi·wo − μi μo` (no division by the sines).
    pub sin_sum: T,
    pub phi: T,
}

impl<T: Real> SlopeGeometry<T> {
    /// `rest` from the normalised 1-D functions `[P0/μ², P1/μ³, H/μ]` of each direction:
    /// `μi μo (μi F0i + μo F0o) + so μi³ F1i + si μo³ F1o + si so (1 + cos Δφ) (μi Hi + μo Ho)`.
    #[inline(always)]
    pub fn rest(&self, fi: [T; 3], fo: [T; 3]) -> T {
        // Grouped per direction: μi (μi (μo F0i + so μi F1i) + Σ Hi) + μo (μo (μi F0o + si μo F1o) + Σ Ho),
        // Σ = si so (1 + cos Δφ).
        let ([mi, mo], [si, so]) = (self.mu, self.sin);
        let part_i = mi.fma((so * mi).fma(fi[1], mo * fi[0]), self.sin_sum * fi[2]);
        let part_o = mo.fma((si * mo).fma(fo[1], mi * fo[0]), self.sin_sum * fo[2]);
        mi.fma(part_i, mo * part_o)
    }

    /// Both directions' coordinates on the ratio table's v axis of roughness m ([`v_axis`]),
    /// `axis = [1/m, 1 − 1/m]`.
    #[inline(always)]
    pub fn v(&self, axis: [T; 2]) -> [T; 2] {
        // Not `array::map`: its closure is not always inlined.
        [v_axis(self.x[0], axis), v_axis(self.x[1], axis)]
    }
}

/// The ratio table's direction axis `v = m sin θ/(m sin θ + μ) = 1/(1 + cot θ/m)` ∈ [0, 1]
/// for roughness m: 0 at the normal, 1 at grazing. Computed from the 1-D axis coordinate
/// `x = sin θ/(sin θ + μ)` ([`axis_of_cos`]) as `v = m x/(1 + (m − 1) x) = x/(x (1 − 1/m) + 1/m)`,
/// an FMA and a division with `axis = [1/m, 1 − 1/m]` ([`ratio_axis_constants`]).
#[inline(always)]
pub fn v_axis<T: Real>(x: T, axis: [T; 2]) -> T {
    x / x.fma(axis[1], axis[0])
}

/// Largest roughness of the ratio table's v axis ([`ratio_axis_roughness`]).
pub const RATIO_AXIS_MAX_M: f64 = 0.5;

/// The roughness whose [`v_axis`] the ratio table of roughness `m` uses: m itself up to
/// [`RATIO_AXIS_MAX_M`], then that. On the axis of m itself, a rougher surface would push the
/// grazing directions, where r changes fastest, into the last cells (at m = 4, θ ≥ 80° is
/// v ≥ 0.96, the last of 19 cells).
pub fn ratio_axis_roughness(m: f64) -> f64 {
    m.min(RATIO_AXIS_MAX_M)
}

/// `[1/m, 1 − 1/m]` for the ratio table's v-axis roughness m of a table of roughness `m0`
/// ([`ratio_axis_roughness`]; what [`v_axis`] takes).
pub fn ratio_axis_constants(m0: f64) -> [f64; 2] {
    let k = 1.0 / ratio_axis_roughness(m0);
    [k, 1.0 - k]
}

/// Inverse of [`v_axis`]: `μ = c/√(1 + c²)`, `c = cot θ = m (1 − v)/v`.
pub fn cos_of_v(v: f64, m: f64) -> f64 {
    if v <= 0.0 {
        return 1.0;
    }
    let c = m * (1.0 - v) / v;
    c / (1.0 + c * c).sqrt()
}

/// The 1-D cell holding axis coordinate `x` ∈ [0, 1] ([`axis_of_cos`] of a clamped cosine,
/// never NaN): its index (an integer-valued float, in packets of eight) and the fraction in it.
#[inline(always)]
pub fn oned_cell<T: Real>(x: T) -> (T, T) {
    let s = x.scale((ONED_NODES - 1) as f64);
    let lower = s.floor().min(T::c((ONED_NODES - 2) as f64));
    (lower, s - lower)
}

/// `[P0/μ², P1/μ³, H/μ, μΛ]` (or their `∂/∂m`) in the cell `(index, fraction)` ([`oned_cell`])
/// of a [`SlopeTable::oned_cells`]-shaped table, whose first packet is `base` (an
/// integer-valued float; zero but in the stacks over m): one packet gather, `K` (3 or 4)
/// linear interpolations of one FMA each (lower node plus fraction times difference).
#[inline(always)]
pub fn oned_in<T: Real, const K: usize>(table: T::Table<'_>, base: T, (index, f): (T, T)) -> [T; K] {
    let p = T::gather8(table, index + base);
    std::array::from_fn(|j| p[j + 4].fma(f, p[j]))
}

/// Trilinear interpolation of a [`SlopeTable::ratio_cells`]-shaped table at `v_i`, `v_o`
/// ([`v_axis`]) and `Δφ` ∈ [0, π]: one packet gather of the cell's eight trilinear
/// coefficients, evaluated by seven FMAs (Horner's scheme, Δφ first).
#[inline(always)]
pub fn ratio_in<T: Real>(cells: T::Table<'_>, v_i: T, v_o: T, phi: T) -> T {
    let (cell, [fi, fo, fc]) = locate(v_i, v_o, phi);
    let n = (R_NODES - 1) as f64;
    let index = (cell[0].scale(n) + cell[1]).fma(T::c(n), cell[2]);
    let c = T::gather8(cells, index);
    let along_phi = |k: usize| c[k + 1].fma(fc, c[k]);
    let (c0, c1) = (along_phi(2).fma(fo, along_phi(0)), along_phi(6).fma(fo, along_phi(4)));
    c1.fma(fi, c0)
}

/// [`ratio_in`] on one layer of a stack of node tables ([`SlopeTable::ratio_nodes`]-shaped,
/// eight gathers): `layer_base` is the index of the layer's first node (an integer-valued
/// float).
#[inline(always)]
pub fn ratio_layer_in<T: Real>(table: T::Table<'_>, layer_base: T, v_i: T, v_o: T, phi: T) -> T {
    let (cell, fractions) = locate(v_i, v_o, phi);
    let n = R_NODES as f64;
    let base = (cell[0].scale(n) + cell[1]).fma(T::c(n), cell[2]) + layer_base;
    let at = |k: usize| {
        let offset = (k >> 2) * R_NODES * R_NODES + ((k >> 1) & 1) * R_NODES + (k & 1);
        T::gather(table, base, offset as u32)
    };
    blend(std::array::from_fn(at), fractions)
}

/// The ratio cell `[i, o, p]` (lower node indices, integer-valued floats) holding the point
/// and the point's fractions in it.
#[inline(always)]
fn locate<T: Real>(v_i: T, v_o: T, phi: T) -> ([T; 3], [T; 3]) {
    let n = (R_NODES - 1) as f64;
    let (i0, fi) = cell(v_i.scale(n), R_NODES);
    let (o0, fo) = cell(v_o.scale(n), R_NODES);
    let (p0, fp) = cell(phi.scale(n / PI), R_NODES);
    ([i0, o0, p0], [fi, fo, fp])
}

/// The trilinear interpolant of a cell's corners (`corners[4a + 2b + d]` at node
/// `(i + a, o + b, p + d)`): seven linear interpolations, Δφ first.
#[inline(always)]
fn blend<T: Real>(corners: [T; 8], [fi, fo, fc]: [T; 3]) -> T {
    let lerp = |a: T, b: T, t: T| (b - a).fma(t, a);
    let [v000, v001, v010, v011, v100, v101, v110, v111] = corners;
    let (v00, v01) = (lerp(v000, v001, fc), lerp(v010, v011, fc));
    let (v10, v11) = (lerp(v100, v101, fc), lerp(v110, v111, fc));
    lerp(lerp(v00, v01, fo), lerp(v10, v11, fo), fi)
}

/// Table coordinate of a direction with cosine `mu` and sine `sin`: `x = sin θ/(sin θ + μ)`
/// ∈ [0, 1] (`x = 1/(1 + cot θ)`, [`v_axis`] at m = 1). Near the normal `x ≈ θ` (uniform in
/// angle); near grazing `1 − x ≈ μ`. Two operations; `μ > 0` (the kernel's clamped cosines).
#[inline(always)]
pub fn axis_of_cos<T: Real>(mu: T, sin: T) -> T {
    sin / (sin + mu)
}

/// Inverse of [`axis_of_cos`]: `cot θ = (1−x)/x`, `μ = (1−x)/√((1−x)² + x²)`.
pub fn cos_of_axis(x: f64) -> f64 {
    let y = 1.0 - x;
    y / (y * y + x * x).sqrt()
}

/// Lower node index (as an integer-valued float) and fraction for the position
/// `s ≥ 0` (in node units) on a grid of `n` nodes, clamped so that `index + 1` is valid;
/// NaN maps to 0. The fraction comes from `floor` (no float → int → float round trip). The
/// callers' positions lie in `[0, n−1]` up to rounding, so no upper clamp of `s` is needed:
/// at most the fraction exceeds 1 by a rounding error.
#[inline(always)]
fn cell<T: Real>(s: T, n: usize) -> (T, T) {
    let s = s.max(T::c(0.0));
    let lower = s.floor().min(T::c((n - 2) as f64));
    (lower, s - lower)
}
