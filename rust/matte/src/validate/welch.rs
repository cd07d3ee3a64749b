//! The two-sample tests every scale of the comparison uses: Welch's unequal-variance t-test
//! of equal means (Welch 1947) with Welch–Satterthwaite degrees of freedom, and Šidák's
//! per-test level for a family of tests (`docs/validation.md#multiple-testing`).

use statrs::distribution::{ContinuousCDF, StudentsT};

/// Two-sided Welch test of equal means from the means and variances of the two mean
/// estimates, with Welch–Satterthwaite degrees of freedom; returns (t, p).
///
/// A floor on the standard error (1e-6 relative plus 1e-12 absolute) keeps deterministic
/// pixels (zero variance in both, e.g. a directly seen constant environment) from turning
/// float rounding into infinite t.
#[inline]
pub fn welch(mean_a: f64, var_a: f64, ka: u32, mean_b: f64, var_b: f64, kb: u32) -> (f64, f64) {
    let floor = (1e-6 * mean_a.abs().max(mean_b.abs())).powi(2) + 1e-24;
    let se2 = var_a + var_b + floor;
    let t = (mean_a - mean_b) / se2.sqrt();
    let dist = StudentsT::new(0.0, 1.0, welch_df(var_a, ka, var_b, kb, floor)).expect("valid t distribution");
    let p = 2.0 * dist.sf(t.abs());
    (t, p.clamp(0.0, 1.0))
}

/// Welch–Satterthwaite degrees of freedom of the difference of two means whose variances
/// (of the mean) are `var_a` and `var_b` from `ka` and `kb` passes; `floor` is added to the
/// variance as in [`welch`]. Clamped to [1, 10⁶].
pub fn welch_df(var_a: f64, ka: u32, var_b: f64, kb: u32, floor: f64) -> f64 {
    let se2 = var_a + var_b + floor;
    let (na, nb) = ((ka as f64 - 1.0).max(1.0), (kb as f64 - 1.0).max(1.0));
    let df = se2 * se2 / (var_a * var_a / na + var_b * var_b / nb + floor * floor).max(1e-300);
    df.clamp(1.0, 1e6)
}

/// Šidák's per-test level for a family of `n` tests at family level `alpha`.
pub fn sidak(alpha: f64, n: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / n.max(1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welch_matches_a_textbook_value() {
        // Equal variances and sizes: t = Δ / sqrt(2 s²/n) with 2n − 2 degrees of freedom.
        // Means 1.0 and 0.0, variance of each mean 0.25 → t = 1/sqrt(0.5) = 1.41421; with n = 10,
        // df = 18; the two-sided p of t(18) at 1.41421 is 0.174363 (numerical integration of the
        // t density, done outside this code).
        let (t, p) = welch(1.0, 0.25, 10, 0.0, 0.25, 10);
        assert!((t - 2f64.sqrt()).abs() < 1e-5, "t = {t}");
        assert!((p - 0.17438).abs() < 2e-4, "p = {p}");
    }

    #[test]
    fn sidak_level_is_exact_for_independent_tests() {
        let a = sidak(0.01, 1000);
        assert!(((1.0 - a).powi(1000) - 0.99).abs() < 1e-12);
    }
}
