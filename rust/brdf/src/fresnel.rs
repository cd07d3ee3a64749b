//! Unpolarized Fresnel reflectance of a smooth dielectric interface and its cosine-weighted
//! hemispherical averages (Born & Wolf, *Principles of Optics*, §1.5.3; Cook & Torrance 1982
//! for the `g` form), in any [`Real`]: f64 for the CPU's precomputation, traced for Wolff's
//! differentiable indices.

use super::quadrature::GaussLegendre;
use super::real::Real;

/// `F(θ, n)` for light arriving at `cos θ = c` from the side of index 1 onto relative index `n`
/// (n < 1: light inside the denser medium). Cook–Torrance `g` form; total internal reflection
/// and `c = 0` give 1. Branch-free and finite on every lane.
#[inline]
pub fn dielectric_reflectance<T: Real>(c: T, n: T) -> T {
    let one = T::c(1.0);
    let c = c.clamp_to(0.0, 1.0);
    let g2 = n.fma(n, c.fma(c, -one));
    let total = g2.le(T::c(0.0)) | c.eq(T::c(0.0));
    let g = g2.safe_sqrt();
    let tiny = T::c(f64::MIN_POSITIVE);
    let a = (g - c) / (g + c).max(tiny);
    let b = c.fma(g + c, -one) / c.fma(g - c, one).max(tiny);
    T::select(total, one, (a * a).scale(0.5) * b.fma(b, one))
}

/// Transmittance `1 − F(θ, n)` of a smooth interface onto relative index `n ≥ 1` (light
/// arriving from the rarer side, no total internal reflection), for the per-eval path.
/// It is the mean of the s and p transmittances (Born & Wolf §1.5.3), with
/// `g = n cos θt = √(n² − 1 + c²)`:
///
/// `T = ½ (Ts + Tp)`, `Ts = 4cg/(c+g)²`, `Tp = 4n²cg/(n²c+g)²`
///
/// (the same `g` as [`dielectric_reflectance`]'s Cook–Torrance form, `Rs = ((c−g)/(c+g))²`,
/// `Rp = ((n²c−g)/(n²c+g))²`). Every term is positive, so unlike `1 − F` it has no
/// cancellation, and it needs one square root and two reciprocals (no ratio `b`). Written as
/// products of ratios in [0, 1] so that nothing overflows for any finite n. `n² − 1` is formed
/// as `(n − 1)(n + 1)`, exact in any precision for n near 1 (where `n·n − 1` cancels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transmittance<T> {
    pub n2: T,
    pub n2_minus_1: T,
}

impl<T: Real> Transmittance<T> {
    /// For relative index `n ≥ 1`. `n²` is capped at 1e30 (n = 1e15, where T < 1e-14 except
    /// at grazing) so that no f32 product overflows into `inf · 0`.
    pub fn new(n: T) -> Self {
        let n = n.min(T::c(1e15));
        Self { n2: n * n, n2_minus_1: (n - T::c(1.0)) * (n + T::c(1.0)) }
    }

    /// `1 − F(θ, n)` at `cos θ = c` (clamped to [0, 1]); `c = 0` gives 0. Relative error
    /// ≤ 1e-6 against f64 (`f32_transmittance_matches_f64_one_minus_reflectance`).
    #[inline(always)]
    pub fn at(&self, c: T) -> T {
        let c = c.clamp_to(0.0, 1.0);
        let g = c.fma(c, self.n2_minus_1).safe_sqrt();
        let n2c = self.n2 * c;
        // c + g = 0 only for c = 0 and n = 1, where T = 0 (F = 1, as dielectric_reflectance).
        let tiny = T::c(f32::MIN_POSITIVE as f64);
        let rs = T::c(1.0) / (c + g).max(tiny);
        let rp = T::c(1.0) / (n2c + g).max(tiny);
        ((c * rs) * (g * rs) + (n2c * rp) * (g * rp)).scale(2.0)
    }
}

impl Transmittance<f64> {
    /// Rounded to f32 for the CPU's per-eval path (the constants formed in f64).
    pub fn rounded(&self) -> Transmittance<f32> {
        Transmittance { n2: self.n2 as f32, n2_minus_1: self.n2_minus_1 as f32 }
    }
}

/// Cosine-weighted hemispherical average seen from outside, `F_dr(n) = 2 ∫_0^1 F(μ, n) μ dμ`,
/// for `n ≥ 1` (smooth integrand: 64 Gauss–Legendre nodes converge to 1e-12).
pub fn diffuse_fresnel_external<T: Real>(n: T) -> T {
    let gl = GaussLegendre::new(64);
    gl.mapped(0.0, 1.0).fold(T::c(0.0), |sum, (mu, w)| (dielectric_reflectance(T::c(mu), n).scale(2.0 * mu * w)) + sum)
}

/// The same average seen from inside, `F_dr(1/n)` for `n ≥ 1` (total internal reflection
/// included), by the identity `1 − F_dr(1/n) = (1 − F_dr(n))/n²`.
pub fn diffuse_fresnel_internal<T: Real>(n: T) -> T {
    T::c(1.0) - (T::c(1.0) - diffuse_fresnel_external(n)) / (n * n)
}

/// Cosine-weighted hemispherical average `F_dr(n) = 2 ∫_0^1 F(μ, n) μ dμ` for any `n > 0`
/// (f64). For n < 1 the integrand is 1 below the critical cosine μc and rises from there like
/// `√(μ − μc)`; the rule is split at μc and the upper part integrated in `μ = μc + (1−μc) w²`,
/// which makes it smooth: an independent check of [`diffuse_fresnel_internal`]'s identity.
pub fn diffuse_fresnel_reflectance(n: f64) -> f64 {
    let gl = GaussLegendre::new(64);
    let f = |mu: f64| 2.0 * dielectric_reflectance(mu, n) * mu;
    if n >= 1.0 {
        gl.integrate(0.0, 1.0, f)
    } else {
        let mu_c = (1.0 - n * n).sqrt(); // cos of the critical angle
        // Below mu_c: total internal reflection, F = 1 exactly.
        let len = 1.0 - mu_c;
        mu_c * mu_c + gl.integrate(0.0, 1.0, |w| f(mu_c + len * w * w) * 2.0 * len * w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn via_rs_rp(c: f64, n: f64) -> f64 {
        let st2 = (1.0 - c * c) / (n * n);
        if st2 >= 1.0 {
            return 1.0;
        }
        let ct = (1.0 - st2).sqrt();
        let rs = (c - n * ct) / (c + n * ct);
        let rp = (n * c - ct) / (n * c + ct);
        0.5 * (rs * rs + rp * rp)
    }

    #[test]
    fn g_form_equals_rs_rp_form() {
        for &n in &[1.2, 1.4, 1.5, 2.0, 1.0 / 1.5] {
            for k in 1..=100 {
                let c = k as f64 / 100.0;
                let d = (dielectric_reflectance(c, n) - via_rs_rp(c, n)).abs();
                assert!(d < 1e-12, "n={n} c={c}: {d}");
            }
        }
    }

    #[test]
    fn reference_values_research_page_3a() {
        assert!((dielectric_reflectance(1.0, 1.5) - 0.04).abs() < 1e-12);
        assert!((diffuse_fresnel_reflectance(1.5) - 0.09178).abs() < 1e-5);
        assert!((diffuse_fresnel_reflectance(1.0 / 1.5) - 0.59635).abs() < 1e-5);
    }

    #[test]
    fn generic_internal_average_matches_the_split_quadrature() {
        for &n in &[1.0, 1.1, 1.33, 1.4, 1.5, 2.4, 10.0] {
            assert!((diffuse_fresnel_internal(n) - diffuse_fresnel_reflectance(1.0 / n)).abs() < 1e-10, "n={n}");
            assert!((diffuse_fresnel_external(n) - diffuse_fresnel_reflectance(n)).abs() < 1e-14, "n={n}");
        }
    }

    #[test]
    fn internal_and_external_averages_obey_the_n_squared_identity() {
        for &n in &[1.1, 1.33, 1.4, 1.5, 1.8, 2.4] {
            let ext = diffuse_fresnel_reflectance(n);
            let int = diffuse_fresnel_reflectance(1.0 / n);
            assert!(((1.0 - int) - (1.0 - ext) / (n * n)).abs() < 1e-12, "n={n}");
        }
    }

    /// The f32 transmittance against `1 − F` in f64 (the Cook–Torrance form, itself checked
    /// against the rs/rp form above): relative error ≤ 1e-6, i.e. a few f32 roundings.
    #[test]
    fn f32_transmittance_matches_f64_one_minus_reflectance() {
        for &n in &[1.0f64, 1.0001, 1.2, 1.4, 1.5046, 2.0, 2.419, 10.0, 1000.0] {
            let t = Transmittance::new(n).rounded();
            let mut worst = 0.0f64;
            for k in 1..=4096 {
                // cosines from 1e-6 to 1, denser towards grazing
                let c = (1e-6f64.ln() * (1.0 - k as f64 / 4096.0)).exp() as f32;
                let want = 1.0 - dielectric_reflectance(c as f64, n);
                let got = t.at(c) as f64;
                worst = worst.max((got - want).abs() / want);
            }
            assert!(worst <= 1e-6, "n={n}: max relative error {worst:e}");
        }
    }

    #[test]
    fn f32_transmittance_is_finite_for_extreme_indices() {
        for n in [1.0f64, 1e6, 1e15, 1e19, 1e25, f64::MAX] {
            for c in [0.0f32, 1e-30, 1e-10, 0.5, 1.0] {
                let t = Transmittance::new(n).rounded().at(c);
                assert!(t.is_finite() && (0.0..=1.0 + 1e-6).contains(&t), "n={n} c={c}: {t}");
            }
        }
    }

    #[test]
    fn grazing_and_total_internal_reflection_give_one() {
        assert_eq!(dielectric_reflectance(0.0, 1.5), 1.0);
        assert_eq!(dielectric_reflectance(0.1, 1.0 / 1.5), 1.0);
        assert_eq!(Transmittance::new(1.5f32).at(0.0), 0.0);
        assert_eq!(Transmittance::new(1.0f32).at(0.0), 0.0);
    }
}
