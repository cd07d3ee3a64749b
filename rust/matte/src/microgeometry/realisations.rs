//! Pooling one measurement over independent realisations of a random surface
//! (`docs/microgeometry.md#patch-independence`). One periodic height-field patch is one draw of
//! the random surface: its BRDF differs from the ensemble's by the patch's own slope statistics,
//! a variation that photons alone cannot see. Averaging R realisations with equal photon counts
//! and taking the interval from the spread of their R means (Student's t, R − 1 degrees of
//! freedom) covers both the photon noise and the patch-to-patch variation.

use super::estimate::Estimate;
use serde::Serialize;

/// A surface's measured value pooled over realisations.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PooledEstimate {
    /// Mean over the realisations (each with the same photon count).
    pub mean: f64,
    /// The 99 % half-width used for comparisons: `realisation_half_width` when there are two or
    /// more realisations, else `photon_half_width`.
    pub half_width: f64,
    /// 99 % half-width from the photons alone, √(Σ hₖ²)/R.
    pub photon_half_width: f64,
    /// 99 % half-width from the spread of the R realisation means (t-interval); `None` for R = 1.
    pub realisation_half_width: Option<f64>,
    pub realisations: usize,
}

impl PooledEstimate {
    /// Whether `x` lies within the interval widened by `slack` (absolute).
    pub fn contains(&self, x: f64, slack: f64) -> bool {
        (x - self.mean).abs() <= self.half_width + slack
    }
}

/// Pools the estimates of one quantity from `R ≥ 1` independent realisations measured with equal
/// photon counts.
pub fn pool(per_realisation: &[Estimate]) -> PooledEstimate {
    let r = per_realisation.len();
    assert!(r > 0, "pool needs at least one realisation");
    let n = r as f64;
    let mean = per_realisation.iter().map(|e| e.mean).sum::<f64>() / n;
    let photon_half_width = per_realisation.iter().map(|e| e.half_width * e.half_width).sum::<f64>().sqrt() / n;
    let realisation_half_width = (r >= 2).then(|| {
        let var = per_realisation.iter().map(|e| (e.mean - mean).powi(2)).sum::<f64>() / (n - 1.0);
        student_t_995(r - 1) * (var / n).sqrt()
    });
    PooledEstimate {
        mean,
        half_width: realisation_half_width.unwrap_or(photon_half_width),
        photon_half_width,
        realisation_half_width,
        realisations: r,
    }
}

/// The 0.995 quantile of Student's t with `dof` ≥ 1 degrees of freedom (two-sided 99 %):
/// tabulated to 30, then the Cornish–Fisher expansion to second order in 1/dof.
pub fn student_t_995(dof: usize) -> f64 {
    const TABLE: [f64; 30] = [
        63.657, 9.925, 5.841, 4.604, 4.032, 3.707, 3.499, 3.355, 3.250, 3.169, 3.106, 3.055, 3.012, 2.977, 2.947,
        2.921, 2.898, 2.878, 2.861, 2.845, 2.831, 2.819, 2.807, 2.797, 2.787, 2.779, 2.771, 2.763, 2.756, 2.750,
    ];
    assert!(dof >= 1, "Student's t needs at least one degree of freedom");
    if dof <= TABLE.len() {
        return TABLE[dof - 1];
    }
    let z = 2.575_829_303_548_901;
    let v = dof as f64;
    let z3 = z * z * z;
    let z5 = z3 * z * z;
    z + (z3 + z) / (4.0 * v) + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * v * v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two-sided probability mass of Student's t density within ±q (Simpson's rule on a fine
    /// grid): a second method for the tabulated quantiles.
    fn t_mass(dof: f64, q: f64) -> f64 {
        let ln_gamma = |x: f64| -> f64 {
            // Lanczos (g = 7, n = 9), accurate to ~1e-13 for x > 0.5.
            const C: [f64; 9] = [
                0.999_999_999_999_809_9,
                676.520_368_121_885_1,
                -1_259.139_216_722_402_8,
                771.323_428_777_653_1,
                -176.615_029_162_140_6,
                12.507_343_278_686_905,
                -0.138_571_095_265_720_12,
                9.984_369_578_019_572e-6,
                1.505_632_735_149_311_6e-7,
            ];
            let x = x - 1.0;
            let t = x + 7.5;
            let s: f64 = C[0] + (1..9).map(|i| C[i] / (x + i as f64)).sum::<f64>();
            0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + s.ln()
        };
        let norm = (ln_gamma((dof + 1.0) / 2.0) - ln_gamma(dof / 2.0)).exp() / (dof * std::f64::consts::PI).sqrt();
        let pdf = |x: f64| norm * (1.0 + x * x / dof).powf(-(dof + 1.0) / 2.0);
        let n = 20_000;
        let h = q / n as f64;
        let s: f64 = (0..=n)
            .map(|i| {
                let w = if i == 0 || i == n {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                w * pdf(i as f64 * h)
            })
            .sum();
        2.0 * s * h / 3.0
    }

    #[test]
    fn t_quantiles_hold_99_percent_of_the_density() {
        for dof in [1usize, 2, 3, 5, 7, 15, 30, 31, 60, 200] {
            let mass = t_mass(dof as f64, student_t_995(dof));
            assert!((mass - 0.99).abs() < 2e-5, "dof {dof}: mass {mass}");
        }
    }

    #[test]
    fn pooling_identical_realisations_has_no_spread() {
        let e = Estimate { mean: 0.2, half_width: 0.01 };
        let p = pool(&[e, e, e, e]);
        assert_eq!(p.mean, 0.2);
        assert_eq!(p.realisation_half_width, Some(0.0));
        assert!((p.photon_half_width - 0.005).abs() < 1e-15);
        let one = pool(&[e]);
        assert_eq!((one.half_width, one.realisation_half_width), (0.01, None));
    }
}
