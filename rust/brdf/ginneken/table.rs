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

use super::shadowing::mu_lambda;
use super::slope_integral::SlopeIntegrator;
use crate::brdf::approx::{at_least, at_most};
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock, Weak};

/// Nodes along each direction axis.
pub const U_NODES: usize = 80;
/// Nodes along the `cos Δφ` axis.
pub const C_NODES: usize = 32;
/// Nodes of the 1-D table of `μΛ(μ)` (same axis): replaces `erfc` and `exp` per direction;
/// interpolation error < 1e-6 of the denominator it enters (covered by the fast-path test).
pub const LAMBDA_NODES: usize = 1024;
/// Gauss–Legendre nodes per radial piece when building (converged to ~1e-7, see tests).
const BUILD_NODES: usize = 24;

/// `I` at the nodes, `[iu_i][iu_o][ic]`. Fixed-size arrays (not a flat `Vec`) so that the
/// compiler sees every index of [`SlopeTable::lookup`] is in range: no bounds checks per eval.
type Grid = [[[f32; C_NODES]; U_NODES]; U_NODES];

#[derive(Debug)]
pub struct SlopeTable {
    data: Box<Grid>,
    /// `μΛ(μ)` at [`LAMBDA_NODES`] points of the direction axis.
    mu_lambda: Box<[f32; LAMBDA_NODES]>,
}

impl SlopeTable {
    /// Tabulates `I` for roughness `m` (parallel over rows; ~66k integrals).
    pub fn build(m: f64) -> Self {
        let (n_u, n_c) = (U_NODES, C_NODES);
        let integrator = SlopeIntegrator::new(BUILD_NODES);
        let mu_at = |k: usize| cos_of_axis(k as f64 / (n_u - 1) as f64);
        let rows: Vec<Vec<f32>> = (0..n_u)
            .into_par_iter()
            .map(|iu_i| {
                let mut row = vec![0.0f32; n_u * n_c];
                for iu_o in iu_i..n_u {
                    for ic in 0..n_c {
                        let c = -1.0 + 2.0 * ic as f64 / (n_c - 1) as f64;
                        row[iu_o * n_c + ic] = integrator.integral(m, mu_at(iu_i), mu_at(iu_o), c.clamp(-1.0, 1.0).acos()) as f32;
                    }
                }
                row
            })
            .collect();
        let mut data: Box<Grid> = vec![[[0.0f32; C_NODES]; U_NODES]; U_NODES].into_boxed_slice().try_into().expect("U_NODES rows");
        for iu_i in 0..n_u {
            for iu_o in iu_i..n_u {
                for ic in 0..n_c {
                    let v = rows[iu_i][iu_o * n_c + ic];
                    data[iu_i][iu_o][ic] = v;
                    data[iu_o][iu_i][ic] = v;
                }
            }
        }
        let mu_lambda = Box::new(std::array::from_fn(|k| {
            let mu = cos_of_axis(k as f64 / (LAMBDA_NODES - 1) as f64);
            mu_lambda(mu, (1.0 - mu * mu).max(0.0).sqrt(), m) as f32
        }));
        Self { data, mu_lambda }
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

    /// Trilinear interpolation at axis coordinates `u_i`, `u_o` ([`axis_of_cos`]) and `c = cos Δφ`.
    #[inline(always)]
    pub fn lookup(&self, u_i: f32, u_o: f32, c: f32) -> f32 {
        let (i0, fi) = cell(u_i * (U_NODES - 1) as f32, U_NODES);
        let (o0, fo) = cell(u_o * (U_NODES - 1) as f32, U_NODES);
        let half = 0.5 * (C_NODES - 1) as f32;
        let (c0, fc) = cell(c.mul_add(half, half), C_NODES);
        // Trilinear interpolation as the weighted sum of the eight corners: the weights are
        // ready before the (usually cache-missing) loads return, after which only a product
        // and a sum remain (nested lerps would leave three dependent levels).
        let (gi, go, gc) = (1.0 - fi, 1.0 - fo, 1.0 - fc);
        let d = &*self.data;
        let pair = |i: usize, o: usize, w: f32| {
            let row = &d[i][o];
            (w * gc).mul_add(row[c0], (w * fc) * row[c0 + 1])
        };
        let v0 = pair(i0, o0, gi * go) + pair(i0, o0 + 1, gi * fo);
        let v1 = pair(i0 + 1, o0, fi * go) + pair(i0 + 1, o0 + 1, fi * fo);
        v0 + v1
    }
}

/// Table coordinate of a direction with cosine `mu`: `x = a/(a+b)`, `a = √(1−μ)`, `b = √μ`.
/// Near the normal `x ≈ a ≈ θ/√2` (uniform in angle); near grazing `μ ≈ (1−x)²`, so the
/// nodes crowd towards the horizon where forward scattering makes `I` fall off like a power
/// of μ. Evaluated as `x = (1 − μ + q)/(1 + 2q)`, `q = ab = √(μ(1−μ))` (multiply `a/(a+b)`
/// above and below by `a+b`): one square root instead of two, all terms ≥ 0 (no cancellation).
#[inline(always)]
pub fn axis_of_cos(mu: f32) -> f32 {
    let mu = at_most(at_least(mu, 0.0), 1.0);
    let one_minus = 1.0 - mu;
    let q = (mu * one_minus).sqrt();
    (one_minus + q) / (1.0 + 2.0 * q)
}

/// Inverse of [`axis_of_cos`]: `μ = (1−x)² / ((1−x)² + x²)`.
pub fn cos_of_axis(x: f64) -> f64 {
    let y = 1.0 - x;
    y * y / (y * y + x * x)
}

impl SlopeTable {
    /// `μΛ(μ)` at axis coordinate `x` ([`axis_of_cos`]), linearly interpolated.
    #[inline(always)]
    pub fn mu_lambda(&self, x: f32) -> f32 {
        let (i, f) = cell(x * (LAMBDA_NODES - 1) as f32, LAMBDA_NODES);
        let t = &self.mu_lambda;
        t[i] + f * (t[i + 1] - t[i])
    }
}

#[cfg(test)]
impl SlopeTable {
    /// `I` at node `(iu_i, iu_o, ic)`, for tests that re-interpolate the table independently.
    pub(crate) fn node(&self, iu_i: usize, iu_o: usize, ic: usize) -> f32 {
        self.data[iu_i][iu_o][ic]
    }

    /// `μΛ` at node `k` of its axis.
    pub(crate) fn lambda_node(&self, k: usize) -> f32 {
        self.mu_lambda[k]
    }
}

/// Lower node index and fraction for the position `s ∈ [0, n−1]` (in node units) on a grid of
/// `n` nodes (clamped so that `index + 1` is valid; NaN maps to 0). The eval calls this five
/// times and its result heads the table lookup's dependency chain, so: the float clamps are
/// single instructions ([`at_least`], where `f32::clamp` compiled to branches); the fraction
/// comes from `floor` (no float → int → float round trip on its path); the index is clamped
/// as an integer, which lets the compiler drop the bounds checks.
#[inline(always)]
fn cell(s: f32, n: usize) -> (usize, f32) {
    let last = (n - 2) as f32;
    let s = at_most(at_least(s, 0.0), last + 1.0);
    let lower = at_most(s.floor(), last);
    ((lower as i32).clamp(0, n as i32 - 2) as usize, s - lower)
}
