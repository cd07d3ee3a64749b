//! The van Ginneken diffuse integral over the Gaussian slope distribution (van Ginneken et al. 1998, eqs. 9–12):
//!
//! `I(wi, wo) = ∬ P22(p, q) (μi − p wi.x − q wi.y)⁺ (μo − p wo.x − q wo.y)⁺ / √(1+p²+q²) dp dq`
//!
//! so that `f_vG = (ρ/π) P_ill+vis I / (μi μo)`. Each facet is Lambertian; `( · )⁺` keeps only
//! facets that face both the light and the viewer; `1/√(1+p²+q²)` is the facet's cos θn area
//! factor combined with the two facet-normal normalisations.
//!
//! [`SlopeIntegrator`] is matte's reference integral. It is semi-analytic: in polar slope
//! coordinates `(t, ψ)` the integral over ψ of the product of two clamped cosines has a closed
//! form (integrate the expanded product over the intersection of the two arcs where each
//! factor is positive), which leaves a 1-D integral over the Rayleigh-distributed slope
//! magnitude t. That one is split where a factor starts to clamp (`t = cot θ`, a
//! `(t − t₀)^{3/2}` kink) and each piece is integrated by Gauss–Legendre after the substitution
//! `t = t₀ + (t₁ − t₀) w²`, which removes the kink. [`midpoint_slope_integral`] is the naive
//! 2-D midpoint rule on [−7m, 7m]² (how the reference tables of `docs/models.md` were
//! computed), kept as an independent check.

use crate::quadrature::GaussLegendre;
use std::f64::consts::{PI, TAU};

/// Gauss–Legendre nodes per radial piece used by the reference integral.
pub const REFERENCE_NODES: usize = 48;

/// Slope magnitudes beyond `TRUNCATION · m` carry weight `e^{−40}` and are ignored.
const TRUNCATION: f64 = 8.94427190999916; // √80

pub struct SlopeIntegrator {
    rule: GaussLegendre,
}

/// One direction as the integral needs it: cosine, sine, azimuth.
#[derive(Clone, Copy, Debug)]
struct Dir {
    mu: f64,
    sin: f64,
}

impl SlopeIntegrator {
    pub fn new(nodes_per_piece: usize) -> Self {
        Self { rule: GaussLegendre::new(nodes_per_piece) }
    }

    /// `I` for directions with cosines `mu_i`, `mu_o` (> 0) and azimuth difference `phi` ∈ [0, π].
    pub fn integral(&self, m: f64, mu_i: f64, mu_o: f64, phi: f64) -> f64 {
        self.integral_and_derivative(m, mu_i, mu_o, phi).0
    }

    /// `(I, ∂I/∂m)`. Only the slope density depends on m: the Rayleigh density of the slope
    /// magnitude `p(t) = (t/m²) e^{−t²/2m²}` has `∂p/∂m = p (t²/m³ − 2/m)`, so the derivative is
    /// the same integral with that factor, on the same nodes. (The truncation at `8.9 m` moves
    /// with m too; its contribution, `~e^{−40}`, is ignored like the tail itself.)
    pub fn integral_and_derivative(&self, m: f64, mu_i: f64, mu_o: f64, phi: f64) -> (f64, f64) {
        let di = Dir { mu: mu_i, sin: (1.0 - mu_i * mu_i).max(0.0).sqrt() };
        let do_ = Dir { mu: mu_o, sin: (1.0 - mu_o * mu_o).max(0.0).sqrt() };
        let t_max = TRUNCATION * m;
        let mut breaks = vec![0.0];
        for d in [di, do_] {
            if d.sin > 0.0 && d.mu / d.sin < t_max {
                breaks.push(d.mu / d.sin);
            }
        }
        breaks.push(t_max);
        breaks.sort_by(|a, b| a.total_cmp(b));
        let inv_m2 = 1.0 / (m * m);
        let radial =
            |t: f64| t * inv_m2 * (-0.5 * t * t * inv_m2).exp() / (1.0 + t * t).sqrt() * angular(di, do_, phi, t);
        let dlog_density = |t: f64| (t * t * inv_m2 - 2.0) / m;
        let (mut sum, mut dsum) = (0.0, 0.0);
        let mut add = |t: f64, weight: f64| {
            let v = radial(t) * weight;
            sum += v;
            dsum += v * dlog_density(t);
        };
        for w in breaks.windows(2) {
            let (t0, t1) = (w[0], w[1]);
            if t1 <= t0 {
                continue;
            }
            if t0 == 0.0 {
                for (t, wt) in self.rule.mapped(t0, t1) {
                    add(t, wt);
                }
            } else {
                // t = t0 + (t1 − t0) w², smooths the (t − t0)^{3/2} onset of clamping.
                let len = t1 - t0;
                for (w, wt) in self.rule.mapped(0.0, 1.0) {
                    add(t0 + len * w * w, wt * 2.0 * len * w);
                }
            }
        }
        (sum, dsum)
    }

    /// `(K, ∂K/∂m)`: the wedge of slopes whose facet faces away from both directions,
    /// `K = E[w (p·wi − μi)⁺ (p·wo − μo)⁺]`, `w = 1/√(1+p²+q²)` (the split
    /// `I = rest + K`, [`Self::direction_functions`]). The same t-quadrature as
    /// [`Self::integral_and_derivative`]; the angular integral of the same product runs over the
    /// intersection of the two arcs where both factors are negative, which exists only beyond
    /// both clamping onsets: one piece from `max(cot θi, cot θo)` to the truncation.
    pub fn wedge_integral_and_derivative(&self, m: f64, mu_i: f64, mu_o: f64, phi: f64) -> (f64, f64) {
        let (di, do_) = (Dir::new(mu_i), Dir::new(mu_o));
        let t_max = TRUNCATION * m;
        let onset = |d: Dir| if d.sin > 0.0 { (d.mu / d.sin).min(t_max) } else { t_max };
        let t0 = onset(di).max(onset(do_));
        if t0 >= t_max {
            return (0.0, 0.0);
        }
        let inv_m2 = 1.0 / (m * m);
        let len = t_max - t0;
        let (mut sum, mut dsum) = (0.0, 0.0);
        for (w, wt) in self.rule.mapped(0.0, 1.0) {
            let t = t0 + len * w * w;
            let v = t * inv_m2 * (-0.5 * t * t * inv_m2).exp() / (1.0 + t * t).sqrt()
                * wedge_angular(di, do_, phi, t)
                * (wt * 2.0 * len * w);
            sum += v;
            dsum += v * (t * t * inv_m2 - 2.0) / m;
        }
        (sum, dsum)
    }

    /// `([P0, P1, H], [∂/∂m of each])` for a direction with cosine `mu`: the 1-D functions of
    /// the split `I = rest + K` (`validation/experiments/slope_fit_results.md`),
    ///
    /// `rest = μo P0(θi) + μi P0(θo) + so P1(θi) + si P1(θo) + (1 + cos Δφ) si so (H(θi) + H(θo))`
    ///
    /// with X, Z ~ N(0, m²) the slope components along and across the direction's azimuth,
    /// `h(X) = E_Z[1/√(1+X²+Z²)]` and `c = cot θ`: `P0 = E[h (μ − sX); 0 < X < c]`,
    /// `P1 = E[h X (μ − sX); 0 < X < c]`, `H = E[h X min(X, c); X > 0]`. Gauss–Legendre in X on
    /// `[0, c]` and `[c, √80 m]`, and in Z on `[0, √80 m]` (h is even in Z). `∂/∂m` weights
    /// the same nodes by `∂ ln(density)/∂m = (X² + Z²)/m³ − 2/m`.
    pub fn direction_functions(&self, m: f64, mu: f64) -> ([f64; 3], [f64; 3]) {
        let d = Dir::new(mu);
        let t_max = TRUNCATION * m;
        let c = if d.sin > 0.0 { (d.mu / d.sin).min(t_max) } else { t_max };
        let (inv_m2, norm) = (1.0 / (m * m), 1.0 / ((2.0 * PI).sqrt() * m));
        let gauss = |x: f64| norm * (-0.5 * x * x * inv_m2).exp();
        // h(X) and E_Z[(Z²/m³ − 1/m)/√(1+X²+Z²)] (Z's share of the density derivative).
        let h = |x: f64| {
            let (mut v, mut dv) = (0.0, 0.0);
            for (z, wz) in self.rule.mapped(0.0, t_max) {
                let e = 2.0 * wz * gauss(z) / (1.0 + x * x + z * z).sqrt();
                v += e;
                dv += e * (z * z * inv_m2 - 1.0) / m;
            }
            (v, dv)
        };
        // The density-weighted h at X and its m-derivative.
        let weight = |x: f64, wx: f64| {
            let (hv, hd) = h(x);
            let g = wx * gauss(x);
            (g * hv, g * (hv * (x * x * inv_m2 - 1.0) / m + hd))
        };
        let (mut f, mut df) = ([0.0; 3], [0.0; 3]);
        for (x, wx) in self.rule.mapped(0.0, c) {
            let (b, db) = weight(x, wx);
            let facing = d.mu - d.sin * x;
            for (k, factor) in [facing, x * facing, x * x].into_iter().enumerate() {
                f[k] += b * factor;
                df[k] += db * factor;
            }
        }
        if c < t_max {
            for (x, wx) in self.rule.mapped(c, t_max) {
                let (b, db) = weight(x, wx);
                f[2] += b * x * c;
                df[2] += db * x * c;
            }
        }
        (f, df)
    }
}

impl Dir {
    fn new(mu: f64) -> Self {
        Dir { mu, sin: (1.0 - mu * mu).max(0.0).sqrt() }
    }
}

/// `(1/2π) ∫ (a1 − b1 cos ψ)⁻ (a2 − b2 cos(ψ − φ))⁻ dψ` with `a = μ`, `b = t sin θ`: the
/// product over the arcs `[off − δ, off + δ]`, `δ = acos(a/b)`, where both factors are negative.
fn wedge_angular(di: Dir, do_: Dir, phi: f64, t: f64) -> f64 {
    let (a1, b1, a2, b2) = (di.mu, t * di.sin, do_.mu, t * do_.sin);
    if b1 <= a1 || b2 <= a2 {
        return 0.0;
    }
    let (d1, d2) = ((a1 / b1).acos(), (a2 / b2).acos());
    arcs_overlap(product_primitive(a1, b1, a2, b2, phi), (-d1, 2.0 * d1), (phi - d2, 2.0 * d2)) / TAU
}

/// `(1/2π) ∫_0^{2π} (a1 − b1 cos ψ)⁺ (a2 − b2 cos(ψ − φ))⁺ dψ` with `a = μ`, `b = t sin θ`.
fn angular(di: Dir, do_: Dir, phi: f64, t: f64) -> f64 {
    let (a1, b1, a2, b2) = (di.mu, t * di.sin, do_.mu, t * do_.sin);
    let prim = product_primitive(a1, b1, a2, b2, phi);
    let total = match (positive_arc(a1, b1, 0.0), positive_arc(a2, b2, phi)) {
        (None, None) => prim(TAU) - prim(0.0),
        (Some((s, l)), None) | (None, Some((s, l))) => prim(s + l) - prim(s),
        (Some(arc1), Some(arc2)) => arcs_overlap(prim, arc1, arc2),
    };
    total / TAU
}

/// An antiderivative in ψ of `(a1 − b1 cos ψ)(a2 − b2 cos(ψ − φ))`, expanded with
/// `cos ψ cos(ψ−φ) = ½[cos φ + cos(2ψ − φ)]`.
fn product_primitive(a1: f64, b1: f64, a2: f64, b2: f64, phi: f64) -> impl Fn(f64) -> f64 {
    let k0 = a1 * a2 + 0.5 * b1 * b2 * phi.cos();
    move |x| k0 * x - a1 * b2 * (x - phi).sin() - a2 * b1 * x.sin() + 0.25 * b1 * b2 * (2.0 * x - phi).sin()
}

/// The integral (by its antiderivative `prim`) over the intersection of two arcs
/// `(start, length)`, the second shifted by −2π, 0 and 2π so that every overlap is found.
fn arcs_overlap(prim: impl Fn(f64) -> f64, (s1, l1): (f64, f64), (s2, l2): (f64, f64)) -> f64 {
    (-1..=1)
        .map(|k| {
            let shift = k as f64 * TAU;
            let (lo, hi) = (s1.max(s2 + shift), (s1 + l1).min(s2 + l2 + shift));
            if hi > lo { prim(hi) - prim(lo) } else { 0.0 }
        })
        .sum()
}

/// The arc `(start, length)` on which `a − b cos(ψ − center_offset) > 0`, or `None` if that
/// holds on the whole circle (a > 0 always here: the facet term is positive at ψ − offset = π).
#[inline]
fn positive_arc(a: f64, b: f64, offset: f64) -> Option<(f64, f64)> {
    if b <= a {
        return None;
    }
    let delta = (a / b).acos();
    Some((offset + delta, TAU - 2.0 * delta))
}

/// Naive midpoint rule on `[−7m, 7m]²` with `n²` cells (400² cells: ≈ 1e-4).
pub fn midpoint_slope_integral(m: f64, mu_i: f64, mu_o: f64, phi: f64, n: usize) -> f64 {
    let si = (1.0 - mu_i * mu_i).max(0.0).sqrt();
    let so = (1.0 - mu_o * mu_o).max(0.0).sqrt();
    let (wix, wiy) = (si, 0.0);
    let (wox, woy) = (so * phi.cos(), so * phi.sin());
    let h = 14.0 * m / n as f64;
    let norm = 1.0 / (2.0 * PI * m * m);
    let mut sum = 0.0;
    for a in 0..n {
        let p = -7.0 * m + (a as f64 + 0.5) * h;
        for b in 0..n {
            let q = -7.0 * m + (b as f64 + 0.5) * h;
            let fi = mu_i - p * wix - q * wiy;
            let fo = mu_o - p * wox - q * woy;
            if fi > 0.0 && fo > 0.0 {
                sum += norm * (-(p * p + q * q) / (2.0 * m * m)).exp() * fi * fo / (1.0 + p * p + q * q).sqrt();
            }
        }
    }
    sum * h * h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn semi_analytic_agrees_with_brute_force_midpoint_rule() {
        let reference = SlopeIntegrator::new(REFERENCE_NODES);
        for &m in &[0.1, 0.3, 0.5, 1.0] {
            for &(ti, to, ph) in &[
                (0.0, 0.0, 0.0),
                (30.0, 60.0, 45.0),
                (75.0, 75.0, 180.0),
                (80.0, 10.0, 0.0),
                (60.0, 60.0, 90.0),
                (85.0, 70.0, 150.0),
            ] {
                let (mi, mo, p) = (f64::to_radians(ti).cos(), f64::to_radians(to).cos(), f64::to_radians(ph));
                let a = reference.integral(m, mi, mo, p);
                // The midpoint rule converges slowly across the clamping kinks: at m = 1, 75/75/180 it
                // is off by 1.9e-4 at 1200², 5.3e-5 at 2400², 1.1e-5 at 4800² (towards this value).
                let b = midpoint_slope_integral(m, mi, mo, p, 2400);
                assert!((a - b).abs() <= 8e-5 * b.abs() + 1e-9, "m={m} ({ti},{to},{ph}): {a} vs {b}");
            }
        }
    }

    #[test]
    fn converged_in_the_number_of_nodes() {
        let coarse = SlopeIntegrator::new(REFERENCE_NODES);
        let fine = SlopeIntegrator::new(160);
        for &m in &[0.05, 0.3, 1.0] {
            for k in 0..=20 {
                let th_i = k as f64 * 4.4f64.to_radians();
                let th_o = (88.0 - k as f64 * 3.0f64).to_radians();
                let p = k as f64 * PI / 20.0;
                let a = coarse.integral(m, th_i.cos(), th_o.cos(), p);
                let b = fine.integral(m, th_i.cos(), th_o.cos(), p);
                assert!((a - b).abs() <= 1e-7 * b.abs().max(1e-3), "m={m} k={k}: {a} vs {b}");
            }
        }
    }

    /// The analytic m-derivative against central differences of the integral itself.
    #[test]
    fn derivative_matches_central_differences() {
        let r = SlopeIntegrator::new(REFERENCE_NODES);
        for &m in &[0.1, 0.3, 0.7] {
            for &(ti, to, ph) in
                &[(0.0, 0.0, 0.0), (30.0, 60.0, 45.0), (75.0, 75.0, 180.0), (80.0, 10.0, 0.0), (85.0, 70.0, 150.0)]
            {
                let (mi, mo, p) = (f64::to_radians(ti).cos(), f64::to_radians(to).cos(), f64::to_radians(ph));
                let h = 1e-3 * m;
                let fd = (r.integral(m + h, mi, mo, p) - r.integral(m - h, mi, mo, p)) / (2.0 * h);
                let (v, d) = r.integral_and_derivative(m, mi, mo, p);
                assert!((d - fd).abs() <= 1e-5 * (d.abs() + v / m), "m={m} ({ti},{to},{ph}): {d} vs {fd} (I = {v})");
            }
        }
    }

    /// `I = rest + K` ([`SlopeIntegrator::direction_functions`],
    /// [`SlopeIntegrator::wedge_integral_and_derivative`]), for the values and the m-derivatives.
    #[test]
    fn integral_splits_into_direction_functions_and_wedge() {
        let r = SlopeIntegrator::new(REFERENCE_NODES);
        let mut worst = (0.0f64, 0.0f64);
        for &m in &[0.05, 0.3, 1.0, 3.0] {
            for &(ti, to, ph) in &[
                (0.0, 0.0, 0.0),
                (30.0, 60.0, 45.0),
                (75.0, 75.0, 180.0),
                (80.0, 10.0, 0.0),
                (85.0, 85.0, 0.0),
                (88.0, 70.0, 20.0),
                (60.0, 89.0, 150.0),
            ] {
                let (mi, mo, p) = (f64::to_radians(ti).cos(), f64::to_radians(to).cos(), f64::to_radians(ph));
                let (si, so) = (f64::to_radians(ti).sin(), f64::to_radians(to).sin());
                let ((fi, dfi), (fo, dfo)) = (r.direction_functions(m, mi), r.direction_functions(m, mo));
                let rest = |a: [f64; 3], b: [f64; 3]| {
                    mo * a[0] + mi * b[0] + so * a[1] + si * b[1] + (1.0 + p.cos()) * si * so * (a[2] + b[2])
                };
                let (k, dk) = r.wedge_integral_and_derivative(m, mi, mo, p);
                let (i, di) = r.integral_and_derivative(m, mi, mo, p);
                let err = ((rest(fi, fo) + k - i) / i).abs();
                let d_err = (rest(dfi, dfo) + dk - di).abs() * m / i;
                worst = (worst.0.max(err), worst.1.max(d_err));
                assert!(err < 1e-9 && d_err < 1e-8, "m={m} ({ti},{to},{ph}): {err:e} {d_err:e}");
            }
        }
        println!("worst relative difference {:e}, of the derivative {:e}", worst.0, worst.1);
    }

    #[test]
    fn smooth_limit_without_roughness_is_the_cosine_product() {
        let r = SlopeIntegrator::new(REFERENCE_NODES);
        let v = r.integral(1e-4, 0.5, 0.8, 1.0);
        assert!((v - 0.4).abs() < 1e-6, "{v}");
    }
}
