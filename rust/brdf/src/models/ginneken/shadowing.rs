//! Shadowing and masking of the Gaussian rough surface (van Ginneken et al. 1998, §3; Smith 1967).
//!
//! Smith's `Λ(θ) = ½ [√(2/π) e^{−a²/2}/a − erfc(a/√2)]`, `a = cot θ / m`, m the per-axis rms
//! slope. The seed paper's `Σ(r, θ)` is this Λ with r = m (its eq. 5 has the same exponent
//! `−cot²θ/(2r²)`). The kernels never use Λ alone: they use `μ Λ(μ)`, which stays finite at
//! grazing (`→ m sin θ/√(2π)`), so that `P_ill+vis / (μi μo)` has no 0·∞.
//!
//! Joint illumination + visibility (van Ginneken et al. 1998; Heitz 2014 eq. 101):
//! `P = 1 / (1 + Λ(θmax) + α(φ) Λ(θmin))`, `α(φ) = 4.41 φ / (4.41 φ + 1)`, φ = |Δφ| ∈ [0, π]
//! in radians. The `height_correlated` alternative is `1 / (1 + Λi + Λo)`.

use crate::real::Real;
use std::f64::consts::PI;

/// Which joint masking-shadowing function to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shadowing {
    /// van Ginneken et al.'s azimuth-dependent correlation (the seed's eq. 5).
    VanGinneken,
    /// Smith height-correlated, no azimuth dependence.
    HeightCorrelated,
}

impl Shadowing {
    pub fn as_str(self) -> &'static str {
        match self {
            Shadowing::VanGinneken => "vginneken",
            Shadowing::HeightCorrelated => "height_correlated",
        }
    }
}

/// `μ Λ(θ)` for a direction with cosine `mu` and sine `sin` (f64 reference).
pub fn mu_lambda(mu: f64, sin: f64, m: f64) -> f64 {
    if sin <= 0.0 || mu <= 0.0 {
        return 0.0; // normal incidence: Λ(0) = 0
    }
    let a = mu / (m * sin);
    if a > 12.0 {
        return 0.0; // e^{−72}: below f64 resolution of the sum it enters
    }
    let v = 0.5 * ((2.0 / PI).sqrt() * m * sin * (-0.5 * a * a).exp() - mu * libm::erfc(a / std::f64::consts::SQRT_2));
    v.max(0.0)
}

/// `∂(μΛ)/∂m = ½ √(2/π) sin θ e^{−a²/2}`, `a = μ/(m sin θ)` (f64; the terms in `∂a/∂m`
/// cancel): the single-roughness table's `∂/∂m` of μΛ.
pub fn d_mu_lambda_dm(mu: f64, sin: f64, m: f64) -> f64 {
    if sin <= 0.0 {
        return 0.0;
    }
    let a = mu / (m * sin);
    0.5 * (2.0 / PI).sqrt() * sin * (-0.5 * a * a).exp()
}

/// `μ Λ(θ)` in any [`Real`], the kernels' form: with `a = μ / (m sin θ)`,
/// `μΛ = m sin θ · g(a)`, `g(a) = ½ [√(2/π) e^{−a²/2} − a erfc(a/√2)]`, and g by a rational
/// fit of degrees 5 and 6 (`mu_lambda_fit.rs`, `validation/generators/fit_mu_lambda.py`) whose error is
/// below 5e-8 of `a + g`, so `μ + μΛ = m sin θ (a + g)`, the sum it enters, is exact to f32
/// rounding. No `exp`, one division besides `a`'s. `a` is clamped at the fit's end (5,
/// where `g/a < 1e-8`), so that normal incidence (`sin θ = 0`) gives 0 with a finite
/// derivative. Differentiable in `m` through the operations themselves (the traced kernels'
/// roughness gradient).
#[inline(always)]
pub fn mu_lambda_closed<T: Real>(mu: T, sin: T, m: T) -> T {
    use super::mu_lambda_fit::{A_MAX, P, Q};
    let ms = m * sin;
    let a = (mu / ms.max(T::c(1e-20))).min(T::c(A_MAX));
    let p = a.fma(a.fma(a.fma(a.fma(a.fma(T::c(P[5]), T::c(P[4])), T::c(P[3])), T::c(P[2])), T::c(P[1])), T::c(P[0]));
    let q = a.fma(
        a.fma(a.fma(a.fma(a.fma(a.fma(T::c(Q[5]), T::c(Q[4])), T::c(Q[3])), T::c(Q[2])), T::c(Q[1])), T::c(Q[0])),
        T::c(1.0),
    );
    (ms * p / q).max(T::c(0.0))
}

/// `α(φ) = 4.41 φ/(4.41 φ + 1)` with φ folded into [0, π] from `cos Δφ`.
#[inline]
pub fn azimuth_correlation(cos_phi: f64) -> f64 {
    let phi = cos_phi.clamp(-1.0, 1.0).acos();
    4.41 * phi / (4.41 * phi + 1.0)
}

/// `(μi μo / P_ill+vis)` as a fraction `(num, den)` with `μi μo / P = den / num`: the
/// per-eval form of [`visibility_denominator`] in any [`Real`], given the azimuth difference
/// `phi` ∈ [0, π] (radians). For `vginneken`, `α = k/(k+1)` (k = 4.41 φ) is folded into the
/// fraction so that the eval divides once: with `a = μmin μmax + μmax Λμmin`,
/// `b = μmin Λμmax`, `den = a(k+1) + k b = a + k(a+b)`, `num = k + 1`.
#[inline(always)]
pub fn visibility_fraction<T: Real>(shadowing: Shadowing, mu_i: T, mu_o: T, ml_i: T, ml_o: T, phi: T) -> (T, T) {
    match shadowing {
        Shadowing::HeightCorrelated => (T::c(1.0), mu_i * mu_o + mu_o * ml_i + mu_i * ml_o),
        Shadowing::VanGinneken => {
            let i_is_min = mu_i.le(mu_o);
            let (mu_min, ml_min) = (T::select(i_is_min, mu_i, mu_o), T::select(i_is_min, ml_i, ml_o));
            let (mu_max, ml_max) = (T::select(i_is_min, mu_o, mu_i), T::select(i_is_min, ml_o, ml_i));
            let a = mu_min * mu_max + mu_max * ml_min;
            let b = mu_min * ml_max;
            let k = phi.scale(4.41);
            (k + T::c(1.0), k.fma(a + b, a))
        }
    }
}

/// `μi μo / P_ill+vis`: the denominator of the van Ginneken BRDF, finite for all μ > 0.
/// Arguments are cosines, sines and `μΛ` of both directions.
#[inline]
pub fn visibility_denominator<T>(
    shadowing: Shadowing,
    mu_i: T,
    mu_o: T,
    ml_i: T,
    ml_o: T,
    alpha: impl FnOnce() -> T,
) -> T
where
    T: Copy + PartialOrd + std::ops::Add<Output = T> + std::ops::Mul<Output = T>,
{
    match shadowing {
        Shadowing::HeightCorrelated => mu_i * mu_o + mu_o * ml_i + mu_i * ml_o,
        Shadowing::VanGinneken => {
            // θmax belongs to the smaller cosine: P = 1/(1 + Λ(μmin) + α Λ(μmax)).
            let (mu_min, ml_min, mu_max, ml_max) =
                if mu_i <= mu_o { (mu_i, ml_i, mu_o, ml_o) } else { (mu_o, ml_o, mu_i, ml_i) };
            mu_min * mu_max + mu_max * ml_min + alpha() * mu_min * ml_max
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quadrature::GaussLegendre;

    /// Smith's definition: `Λ = (1/cot θ) ∫_{cot θ}^{∞} (q − cot θ) p(q) dq`, p the 1-D slope
    /// density N(0, m²) along the direction's azimuth.
    fn lambda_by_definition(theta: f64, m: f64) -> f64 {
        let cot = 1.0 / theta.tan();
        let gl = GaussLegendre::new(200);
        let p = |q: f64| (-(q * q) / (2.0 * m * m)).exp() / ((2.0 * PI).sqrt() * m);
        gl.integrate(cot, cot + 40.0 * m, |q| (q - cot) * p(q)) / cot
    }

    #[test]
    fn lambda_closed_form_matches_smith_definition() {
        for &m in &[0.1, 0.3, 0.5, 1.0] {
            for deg in [10.0f64, 30.0, 60.0, 75.0, 85.0, 89.0] {
                let t = deg.to_radians();
                let got = mu_lambda(t.cos(), t.sin(), m) / t.cos();
                let want = lambda_by_definition(t, m);
                assert!((got - want).abs() <= 1e-9 + 1e-7 * want, "m={m} θ={deg}: {got} vs {want}");
            }
        }
    }

    /// The kernels' closed form against the f64 reference (libm's erfc): error below 1e-7 of
    /// `μ + μΛ` (the sum the kernels use) over roughness and angle, evaluated in f64 (the
    /// fit's error alone) and within 4e-7 in f32 (what the kernels run: a few roundings of its chain).
    #[test]
    fn closed_form_mu_lambda_matches_the_reference() {
        for &m in &[0.02, 0.1, 0.3, 1.0, 4.0] {
            for k in 0..=900 {
                let t = (k as f64 * 0.1).to_radians();
                let (mu, sin) = (t.cos(), t.sin());
                let want = mu_lambda(mu, sin, m);
                let got64 = mu_lambda_closed(mu, sin, m);
                let tol64 = 1e-7 * (mu + want) + 1e-12;
                assert!((got64 - want).abs() <= tol64, "f64 m={m} θ={}: {got64} vs {want}", k as f64 * 0.1);
                let got32 = mu_lambda_closed(mu as f32, sin as f32, m as f32) as f64;
                let tol = 4e-7 * (mu + want) + 1e-9;
                assert!((got32 - want).abs() <= tol, "f32 m={m} θ={}: {got32} vs {want}", k as f64 * 0.1);
            }
        }
        // Normal incidence: zero, and a finite derivative in m (dual numbers).
        use crate::dual::Dual;
        let d = mu_lambda_closed(Dual::c(1.0), Dual::c(0.0), Dual::variable(0.3));
        assert_eq!((d.v, d.d), (0.0, 0.0));
        // ∂(μΛ)/∂m = ½ √(2/π) sin θ e^{−a²/2} (the a-terms cancel; `d_mu_lambda_dm`), against the
        // dual numbers, and that closed form against central differences.
        // The fit moves it by less than 1e-5 of (μ + μΛ)/m: the elasticity of μ + μΛ in m,
        // which is what the roughness gradient of f sees, is right to 1e-5.
        for &m in &[0.1, 0.5, 2.0] {
            for k in 1..=89 {
                let t = (k as f64).to_radians();
                let (mu, sin) = (t.cos(), t.sin());
                let d = mu_lambda_closed(Dual::c(mu), Dual::c(sin), Dual::variable(m)).d;
                let want = d_mu_lambda_dm(mu, sin, m);
                let tol = 1e-5 * (mu + mu_lambda(mu, sin, m)) / m;
                assert!((d - want).abs() <= tol, "m={m} θ={k}: {d} vs {want}");
                // The closed form itself against central differences of the f64 reference.
                let h = 1e-5 * m;
                let fd = (mu_lambda(mu, sin, m + h) - mu_lambda(mu, sin, m - h)) / (2.0 * h);
                assert!((fd - want).abs() <= 1e-7 * (mu + mu_lambda(mu, sin, m)) / m, "m={m} θ={k}: {fd} vs {want}");
            }
        }
    }

    #[test]
    fn correlation_limits() {
        assert_eq!(azimuth_correlation(1.0), 0.0);
        assert!((azimuth_correlation(0.0) - 0.874).abs() < 1e-3);
        assert!((azimuth_correlation(-1.0) - 0.933).abs() < 1e-3);
    }
}
