//! Unpolarized Fresnel reflectance of a smooth dielectric interface and its cosine-weighted
//! hemispherical averages (research page §3a).

use super::quadrature::GaussLegendre;

/// `F(θ, n)` for light arriving at `cos θ = c` from the side of index 1 onto relative index `n`
/// (n < 1: light inside the denser medium). Cook–Torrance `g` form; total internal reflection
/// and `c = 0` give 1.
#[inline]
pub fn fresnel_dielectric(c: f64, n: f64) -> f64 {
    let c = c.clamp(0.0, 1.0);
    let g2 = n * n - 1.0 + c * c;
    if g2 <= 0.0 || c == 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

/// f32 version for the hot path (same formula).
#[inline]
pub fn fresnel_dielectric_f32(c: f32, n: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    let g2 = n * n - 1.0 + c * c;
    if g2 <= 0.0 || c == 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

/// Cosine-weighted hemispherical average `F_dr(n) = 2 ∫_0^1 F(μ, n) μ dμ`.
/// For n < 1 the integrand is 1 below the critical cosine μc and rises from there like
/// `√(μ − μc)`; the rule is split at μc and the upper part integrated in `μ = μc + (1−μc) w²`,
/// which makes it smooth (identity `1 − F_dr(1/n) = (1 − F_dr(n))/n²` holds to 1e-12).
pub fn diffuse_fresnel_reflectance(n: f64) -> f64 {
    let gl = GaussLegendre::new(64);
    let f = |mu: f64| 2.0 * fresnel_dielectric(mu, n) * mu;
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
                let d = (fresnel_dielectric(c, n) - via_rs_rp(c, n)).abs();
                assert!(d < 1e-12, "n={n} c={c}: {d}");
            }
        }
    }

    #[test]
    fn reference_values_research_page_3a() {
        assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-12);
        assert!((diffuse_fresnel_reflectance(1.5) - 0.09178).abs() < 1e-5);
        assert!((diffuse_fresnel_reflectance(1.0 / 1.5) - 0.59635).abs() < 1e-5);
    }

    #[test]
    fn internal_and_external_averages_obey_the_n_squared_identity() {
        for &n in &[1.1, 1.33, 1.4, 1.5, 1.8, 2.4] {
            let ext = diffuse_fresnel_reflectance(n);
            let int = diffuse_fresnel_reflectance(1.0 / n);
            assert!(((1.0 - int) - (1.0 - ext) / (n * n)).abs() < 1e-12, "n={n}");
        }
    }

    #[test]
    fn grazing_and_total_internal_reflection_give_one() {
        assert_eq!(fresnel_dielectric(0.0, 1.5), 1.0);
        assert_eq!(fresnel_dielectric(0.1, 1.0 / 1.5), 1.0);
        assert_eq!(fresnel_dielectric_f32(0.0, 1.5), 1.0);
    }
}
