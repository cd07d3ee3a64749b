//! Sampling routines against their pdfs with Mitsuba's chi-square test (`docs/validation.md#kernel-checks`):
//! every model configuration at incidence 0°, 45° and 80°, Šidák-corrected over all cases.

use crate::common::{self, catalogue, chi2_sampling, sidak};
use glam::Vec3;

#[test]
#[ignore = "thorough tier: `make test` runs it (cargo test -p matte-brdf -- --ignored)"]
fn sampling_matches_pdf() {
    let models = catalogue();
    let angles = [0.0f32, 45.0, 80.0];
    let level = sidak(models.len() * angles.len());
    let mut failures = vec![];
    for (i, (label, bsdf)) in models.iter().enumerate() {
        for (j, deg) in angles.iter().enumerate() {
            let t = deg.to_radians();
            let wi = Vec3::new(t.sin(), 0.0, t.cos());
            match chi2_sampling(bsdf, wi, (i * 16 + j) as u64) {
                Ok(o) if o.p_value >= level => {}
                Ok(o) => failures.push(format!(
                    "{label} θi={deg}: p = {:.3e} < {level:.3e} (χ² = {:.1}, dof {})",
                    o.p_value, o.statistic, o.dof
                )),
                Err(e) => failures.push(format!("{label} θi={deg}: {e}")),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The test must be able to fail: a pdf that disagrees with the sampler by a mild
/// cos^1.1-versus-cos tilt (both normalised) is rejected, while Lambert itself passes.
#[test]
fn chi_square_rejects_a_wrong_pdf() {
    use glam::Vec2;
    use matte_brdf::sampling::square_to_cosine_hemisphere;
    use matte_brdf::{BrdfSample, DiffuseBrdf};
    struct Tilted;
    impl DiffuseBrdf for Tilted {
        fn eval<const N: usize>(&self, _: Vec3, wo: Vec3, r: [f32; N]) -> [f32; N] {
            if wo.z > 0.0 { r.map(|x| x / std::f32::consts::PI) } else { [0.0; N] }
        }
        // ∫ cos^1.1 dω = 2π/2.1
        fn pdf(&self, _: Vec3, wo: Vec3) -> f32 {
            wo.z.max(0.0).powf(1.1) * 2.1 / (2.0 * std::f32::consts::PI)
        }
        // Draws cosine-weighted directions but reports the tilted density.
        fn sample<const N: usize>(&self, wi: Vec3, u: Vec2, r: [f32; N]) -> Option<BrdfSample<N>> {
            let wo = square_to_cosine_hemisphere(u);
            let pdf = self.pdf(Vec3::Z, wo);
            let f = self.eval(wi, wo, r);
            Some(BrdfSample { wo, pdf, weight: f.map(|x| x * wo.z / pdf) })
        }
    }
    let wrong = chi2_sampling(&Tilted, Vec3::Z, 99);
    assert!(
        wrong.is_err() || wrong.as_ref().unwrap().p_value < sidak(1),
        "a wrong pdf passed: p = {:?}",
        wrong.map(|o| o.p_value)
    );
    let right = chi2_sampling(&common::model("lambert", &[]), Vec3::Z, 99).unwrap();
    assert!(right.p_value >= sidak(1), "lambert must pass: p = {}", right.p_value);
}
