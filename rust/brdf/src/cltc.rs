//! Importance sampling by a *clipped linearly transformed cosine* (CLTC) mixed with uniform
//! hemisphere sampling: the sampler of EON (Portsmouth, Kutz & Hill, JCGT 14(1) 2025, §4,
//! reference code `portsmouth/EON-diffuse`), written once over [`Real`] so that the f32, the
//! 8-wide and the traced kernels share it. A model supplies the lobe's matrix and mixture
//! probability at the fixed direction's `μ = cos θi` ([`ClippedLtc`]); the fits are in the
//! model's file.
//!
//! The lobe, in the frame whose x axis is `wi`'s azimuth (`wi` in the +x half of the xz
//! plane), is `wo ∝ M h` with `M = [[a, 0, b], [0, c, 0], [d, 0, 1]]` and `h` cosine-distributed
//! over the part of the hemisphere that `M` keeps above the horizon (`d h.x + h.z > 0`). Under
//! Malley's projection that part is the unit disk minus a cap, of area `π s` with
//! `s = ½ (1 + 1/√(1 + d²))`; each horizontal chord of the disk is mapped affinely onto its kept
//! part, which keeps the distribution uniform. The density of `wo` is then
//! `D(h) |det M⁻¹| / |M⁻¹ wo|³ = (det M / |q|²)² max(q.z, 0) / (π s)` with `q = adj(M) wo`.
//! Near the horizon on the side away from `wi` the clipped lobe has no density; the uniform
//! component (probability `p_uniform`) keeps the mixture positive on the whole hemisphere.
//!
//! matte's choices where the reference leaves room: `d` is clamped to ≤ 0 (the fit turns
//! positive by 0.0035·r for μ > 0.99991, where the reference's sampler and pdf disagree); the
//! lobe choice reuses `u1` with a strict `<` (no 0/0 at `p_uniform = 0`); the disk point is
//! Mitsuba's concentric map, the uniform hemisphere Mitsuba's `square_to_uniform_hemisphere`;
//! the sample's pdf is [`ClippedLtc::pdf`] at the sampled direction, so `pdf(sample)` equals
//! `pdf(eval)` exactly.

use super::real::{Real, V3};
use super::sampling::concentric_disk;
use std::f64::consts::{FRAC_1_PI, PI};

/// One CLTC lobe: the matrix entries and the uniform component's probability at one `μ`.
#[derive(Clone, Copy, Debug)]
pub struct ClippedLtc<T> {
    pub a: T,
    pub b: T,
    pub c: T,
    /// Clamped to ≤ 0 by [`ClippedLtc::new`].
    pub d: T,
    /// Probability of the uniform hemisphere component, in [0, 1).
    pub p_uniform: T,
}

/// The unit vector along `wi`'s azimuth, `(1, 0)` when `wi` is the normal: the lobe frame's
/// x axis (its y axis is `z × x`). The same rule in [`ClippedLtc::sample`] and
/// [`ClippedLtc::pdf`].
#[inline(always)]
fn azimuth<T: Real>(wi: V3<T>) -> (T, T) {
    let len2 = wi.x.fma(wi.x, wi.y * wi.y);
    let tilted = len2.gt(T::c(1e-24));
    let inv = T::c(1.0) / len2.max(T::c(1e-24)).sqrt();
    (T::select(tilted, wi.x * inv, T::c(1.0)), T::select(tilted, wi.y * inv, T::c(0.0)))
}

impl<T: Real> ClippedLtc<T> {
    #[inline(always)]
    pub fn new(a: T, b: T, c: T, d: T, p_uniform: T) -> Self {
        Self { a, b, c, d: d.min(T::c(0.0)), p_uniform }
    }

    /// The clipped disk's area over π: `½ (1 + 1/√(1 + d²))`.
    #[inline(always)]
    fn kept_fraction(&self) -> T {
        let v = T::c(1.0) / self.d.fma(self.d, T::c(1.0)).sqrt();
        (T::c(1.0) + v).scale(0.5)
    }

    /// The mixture's density at `wo`, for `wi` and `wo` above the surface (finite for every
    /// input; callers mask the others).
    #[inline(always)]
    pub fn pdf(&self, wi: V3<T>, wo: V3<T>) -> T {
        let (xx, xy) = azimuth(wi);
        // wo in the lobe frame, then q = adj(M) w = det M · M⁻¹ w.
        let wx = xx.fma(wo.x, xy * wo.y);
        let wy = xx.fma(wo.y, -(xy * wo.x));
        let a_bd = self.a - self.b * self.d;
        let qx = self.c * (wx - self.b * wo.z);
        let qy = a_bd * wy;
        let qz = self.c * (self.a * wo.z - self.d * wx);
        let det = self.c * a_bd;
        let q2 = (qx.fma(qx, qy * qy).fma(T::c(1.0), qz * qz)).max(T::c(1e-20));
        let jac = det / q2;
        let lobe = jac * jac * qz.max(T::c(0.0)) * T::c(FRAC_1_PI) / self.kept_fraction();
        self.p_uniform.fma(T::c(0.5 / PI), (T::c(1.0) - self.p_uniform) * lobe)
    }

    /// Draws `wo` for `wi` above the surface from two uniform numbers: `(wo, pdf)`. `u1` picks
    /// the component and is then rescaled to [0, 1) for it.
    #[inline(always)]
    pub fn sample(&self, wi: V3<T>, u1: T, u2: T) -> (V3<T>, T) {
        let one = T::c(1.0);
        let p_u = self.p_uniform;
        let uniform = u1.lt(p_u);
        let u1 = T::select(uniform, u1 / p_u.max(T::c(1e-20)), (u1 - p_u) / (one - p_u));
        let (px, py) = concentric_disk(u1.min(T::c(1.0)), u2);

        // Uniform hemisphere (Mitsuba's square_to_uniform_hemisphere): z = 1 − r², in the
        // shading frame.
        let r2 = px.fma(px, py * py);
        let grow = (T::c(2.0) - r2).safe_sqrt();
        let uniform_wo = V3::new(px * grow, py * grow, one - r2);

        // Clipped cosine: each chord at height y squashed onto its kept part [−L, v L]
        // (mirrored so that the cap removed is on the −x side, as d ≤ 0 makes it).
        let s = self.kept_fraction();
        let half_chord = (one - py * py).safe_sqrt();
        let hx = -(one - s).fma(half_chord, s * px);
        let hz = (one - hx * hx - py * py).safe_sqrt();
        let mx = self.a.fma(hx, self.b * hz);
        let my = self.c * py;
        let mz = self.d.fma(hx, hz);
        let inv = one / mx.fma(mx, my * my).fma(one, mz * mz).max(T::c(1e-20)).sqrt();
        let (xx, xy) = azimuth(wi);
        let (lx, ly, lz) = (mx * inv, my * inv, mz * inv);
        let lobe_wo = V3::new(xx.fma(lx, -(xy * ly)), xy.fma(lx, xx * ly), lz);

        let wo = V3::new(
            T::select(uniform, uniform_wo.x, lobe_wo.x),
            T::select(uniform, uniform_wo.y, lobe_wo.y),
            T::select(uniform, uniform_wo.z, lobe_wo.z),
        );
        (wo, self.pdf(wi, wo))
    }
}

/// A fitted CLTC sampler (`rust/brdf/src/sampler_fits.rs`, written by
/// `validation/generators/fit_samplers.py`): each parameter of [`ClippedLtc`] is
///
/// `p_k(μ, t) = base_k + t g_k(μ) Σ_ij C[k][i][j] μ^i t^j`
///
/// with `base = (1, 0, 1, 0, 0)` (the cosine: the sampler at t = 0), `g_k = sin θi` (the
/// cosine's value at normal incidence too) or 1 (`free_at_normal[k]`), and `t ∈ [0, 1]` the
/// model's roughness variable. Then `a, c ≥ 0.05`, `d ≤ 0` and `p_uniform ∈ [−0.1 d, 0.9]`:
/// wherever the lobe is clipped the uniform share is positive, so that no direction is left
/// unsampled, whatever the polynomials do between the fit's grid points. Polynomials only
/// (Horner, no gathers, no division): cheap in every [`Real`], and finite for every input.
#[derive(Clone, Copy, Debug)]
pub struct CltcFit<const NMU: usize, const NT: usize> {
    /// `C[k][i][j]`, k over (a, b, c, d, p_uniform), i the power of μ, j the power of t.
    pub coefficients: [[[f64; NT]; NMU]; 5],
    pub free_at_normal: [bool; 5],
}

impl<const NMU: usize, const NT: usize> CltcFit<NMU, NT> {
    /// The sampler at `μ = cos θi` and roughness variable `t` (both clamped into [0, 1]).
    #[inline(always)]
    pub fn sampler<T: Real>(&self, mu: T, t: T) -> ClippedLtc<T> {
        let mu = mu.clamp_to(0.0, 1.0);
        let t = t.clamp_to(0.0, 1.0);
        let sin_t = t * (T::c(1.0) - mu * mu).safe_sqrt();
        let term = |k: usize| {
            let c = &self.coefficients[k];
            let mut acc = T::c(0.0);
            for i in (0..NMU).rev() {
                let mut q = T::c(c[i][NT - 1]);
                for j in (0..NT - 1).rev() {
                    q = q.fma(t, T::c(c[i][j]));
                }
                acc = if i == NMU - 1 { q } else { acc.fma(mu, q) };
            }
            acc * if self.free_at_normal[k] { t } else { sin_t }
        };
        let one = T::c(1.0);
        let d = term(3).min(T::c(0.0));
        let p_uniform = term(4).max(d.scale(-0.1)).min(T::c(0.9));
        ClippedLtc::new((one + term(0)).max(T::c(0.05)), term(1), (one + term(2)).max(T::c(0.05)), d, p_uniform)
    }
}

/// How a model with its own sampler draws directions (its `sampling` parameter).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sampling {
    /// The model's clipped linearly transformed cosine (`rust/brdf/src/cltc.rs`).
    Cltc,
    /// Mitsuba's cosine-weighted sampling, as `diffuse`: the default (it renders the
    /// measured scenes as efficiently, `docs/sampling.md#scene-level`).
    Cosine,
}

impl Sampling {
    pub const CHOICES: &'static [&'static str] = &["cosine", "cltc"];

    pub fn parse(word: &str) -> Self {
        if word == "cltc" { Sampling::Cltc } else { Sampling::Cosine }
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Sampling::Cltc => "cltc",
            Sampling::Cosine => "cosine",
        }
    }
}
