//! The fast path: the slope integral `I(θi, θo, Δφ)` tabulated per roughness and interpolated
//! trilinearly. Only `I` is tabulated; the visibility term `P_ill+vis/(μi μo)` is evaluated in
//! closed form at run time, because its `4.41 φ` azimuth factor and its `max/min(θi, θo)` kink
//! interpolate badly while `I` is smooth: without clamping it is exactly
//! `μi μo E[1/√(1+t²)] + sin θi sin θo cos Δφ · ½E[t²/√(1+t²)]`.
//!
//! Axes (chosen so that `I` is close to linear along each of them):
//! * `x = √(1−μ) / (√(1−μ) + √μ)` for each direction ([`axis_of_cos`]): about uniform in angle
//!   near the normal, crowding towards grazing where forward scattering makes `I` fall off
//!   like a power of μ; two square roots, no trig. Measured (m = 0.3, 3000 configurations):
//!   the plain `√(1−μ)` axis needed 128 nodes for the error this one reaches with 80.
//! * `c = cos Δφ` ∈ [−1, 1]: `I` is linear in `c` wherever no facet is clamped.
//! `I(θi, θo, Δφ) = I(θo, θi, Δφ)`, so only `x_i ≤ x_o` is integrated and the rest mirrored.

use super::shadowing::mu_lambda;
use super::slope_integral::SlopeIntegrator;
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

#[derive(Debug)]
pub struct SlopeTable {
    /// `data[(iu_i * U_NODES + iu_o) * C_NODES + ic]`.
    data: Vec<f32>,
    /// `μΛ(μ)` at [`LAMBDA_NODES`] points of the direction axis.
    mu_lambda: Vec<f32>,
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
        let mut data = vec![0.0f32; n_u * n_u * n_c];
        for iu_i in 0..n_u {
            for iu_o in iu_i..n_u {
                for ic in 0..n_c {
                    let v = rows[iu_i][iu_o * n_c + ic];
                    data[(iu_i * n_u + iu_o) * n_c + ic] = v;
                    data[(iu_o * n_u + iu_i) * n_c + ic] = v;
                }
            }
        }
        let mu_lambda = (0..LAMBDA_NODES)
            .map(|k| {
                let mu = cos_of_axis(k as f64 / (LAMBDA_NODES - 1) as f64);
                mu_lambda(mu, (1.0 - mu * mu).max(0.0).sqrt(), m) as f32
            })
            .collect();
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
    #[inline]
    pub fn lookup(&self, u_i: f32, u_o: f32, c: f32) -> f32 {
        let (n_u, n_c) = (U_NODES, C_NODES);
        let (i0, fi) = cell(u_i, n_u);
        let (o0, fo) = cell(u_o, n_u);
        let (c0, fc) = cell(0.5 * (c + 1.0), n_c);
        let at = |i: usize, o: usize| (i * n_u + o) * n_c + c0;
        let d = &self.data;
        let lerp_c = |k: usize| d[k] + fc * (d[k + 1] - d[k]);
        let v00 = lerp_c(at(i0, o0));
        let v01 = lerp_c(at(i0, o0 + 1));
        let v10 = lerp_c(at(i0 + 1, o0));
        let v11 = lerp_c(at(i0 + 1, o0 + 1));
        let v0 = v00 + fo * (v01 - v00);
        let v1 = v10 + fo * (v11 - v10);
        v0 + fi * (v1 - v0)
    }
}

/// Table coordinate of a direction with cosine `mu`: `x = a/(a+b)`, `a = √(1−μ)`, `b = √μ`.
/// Near the normal `x ≈ a ≈ θ/√2` (uniform in angle); near grazing `μ ≈ (1−x)²`, so the
/// nodes crowd towards the horizon where forward scattering makes `I` fall off like a power
/// of μ.
#[inline]
pub fn axis_of_cos(mu: f32) -> f32 {
    let a = (1.0 - mu).max(0.0).sqrt();
    let b = mu.max(0.0).sqrt();
    a / (a + b)
}

/// Inverse of [`axis_of_cos`]: `μ = (1−x)² / ((1−x)² + x²)`.
pub fn cos_of_axis(x: f64) -> f64 {
    let y = 1.0 - x;
    y * y / (y * y + x * x)
}

impl SlopeTable {
    /// `μΛ(μ)` at axis coordinate `x` ([`axis_of_cos`]), linearly interpolated.
    #[inline]
    pub fn mu_lambda(&self, x: f32) -> f32 {
        let (i, f) = cell(x, LAMBDA_NODES);
        let t = &self.mu_lambda;
        t[i] + f * (t[i + 1] - t[i])
    }
}

/// Lower node index and fraction for `x ∈ [0, 1]` on a grid of `n` nodes (clamped so that
/// `index + 1` is valid).
#[inline]
fn cell(x: f32, n: usize) -> (usize, f32) {
    let s = x.clamp(0.0, 1.0) * (n - 1) as f32;
    let i = (s as usize).min(n - 2);
    (i, s - i as f32)
}
