//! Model-independent properties, run over every model and several parameter sets
//! (`common::catalogue`): reciprocity, sample weight == eval·cos/pdf, agreement of the
//! sampling weights with the directional albedo (Mitsuba's `test_hair.py` furnace
//! method), no NaN/Inf anywhere, zero below the horizon.

use crate::common::{Pcg32, PcgExt, catalogue};
use glam::Vec3;
use matte_brdf::{DiffuseBrdf, DiffuseModel};

#[test]
fn reciprocity_on_random_pairs() {
    let mut rng = Pcg32::new(1, 7);
    for (label, bsdf) in catalogue() {
        for _ in 0..20_000 {
            let (a, b) = (rng.upper_hemisphere(), rng.upper_hemisphere());
            let rho = [0.9f32, 0.5, 0.1];
            let (f, g) = (bsdf.eval(a, b, rho), bsdf.eval(b, a, rho));
            for k in 0..3 {
                let tol = 1e-5 * f[k].abs().max(g[k].abs()) + 1e-12;
                assert!((f[k] - g[k]).abs() <= tol, "{label}: f({a}, {b}) = {} but f({b}, {a}) = {}", f[k], g[k]);
            }
        }
    }
}

#[test]
fn sample_weight_is_eval_cos_over_pdf() {
    let mut rng = Pcg32::new(2, 7);
    for (label, bsdf) in catalogue() {
        for _ in 0..20_000 {
            let wi = rng.upper_hemisphere();
            let rho = [0.8f32, 0.3];
            let Some(s) = bsdf.sample(wi, rng.next_vec2(), rho) else {
                panic!("{label}: no sample for wi {wi} above the surface")
            };
            assert!(
                (s.pdf - bsdf.pdf(wi, s.wo)).abs() <= 1e-6 * s.pdf,
                "{label}: sample pdf {} vs pdf() {}",
                s.pdf,
                bsdf.pdf(wi, s.wo)
            );
            let f = bsdf.eval(wi, s.wo, rho);
            for (k, fk) in f.iter().enumerate().take(2) {
                let want = fk * s.wo.z / s.pdf;
                assert!(
                    (s.weight[k] - want).abs() <= 1e-5 * want.abs() + 1e-12,
                    "{label}: weight {} vs {want}",
                    s.weight[k]
                );
            }
        }
    }
}

/// Mean sample weight (importance-sampled furnace) and a uniform-hemisphere estimate of
/// `∫ f cos` both equal `albedo()`. 4·10^5 samples each; tolerance 4 standard errors.
#[test]
#[ignore = "thorough tier: `make test` runs it (cargo test -p matte-brdf -- --ignored)"]
fn furnace_estimates_agree_with_albedo() {
    let mut rng = Pcg32::new(3, 7);
    for (label, bsdf) in catalogue() {
        for deg in [0.0f32, 45.0, 80.0] {
            let t = deg.to_radians();
            let wi = Vec3::new(t.sin(), 0.0, t.cos());
            let want = bsdf.albedo(t.cos() as f64, 1.0).value;
            let n = 400_000;
            let (mut s1, mut s2, mut u1, mut u2) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
            for _ in 0..n {
                let w = bsdf.sample(wi, rng.next_vec2(), [1.0]).map_or(0.0, |s| s.weight[0] as f64);
                s1 += w;
                s2 += w * w;
                let wo = rng.upper_hemisphere();
                let x = bsdf.eval(wi, wo, [1.0])[0] as f64 * wo.z as f64 * 2.0 * std::f64::consts::PI;
                u1 += x;
                u2 += x * x;
            }
            for (name, m1, m2) in [("importance", s1, s2), ("uniform", u1, u2)] {
                let mean = m1 / n as f64;
                let se = ((m2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt();
                assert!(
                    (mean - want).abs() <= 4.0 * se + 2e-4,
                    "{label} θi={deg}: {name} estimate {mean:.5} ± {se:.5} vs albedo {want:.5}"
                );
            }
        }
    }
}

/// 10^6 random pairs per model, a third of them grazing (cos < 1e-6, down to denormals) and
/// a third below the horizon: never NaN or Inf; exactly 0 below the horizon.
#[test]
#[ignore = "thorough tier: `make test` runs it (cargo test -p matte-brdf -- --ignored)"]
fn finite_everywhere_and_zero_below_horizon() {
    let mut rng = Pcg32::new(4, 7);
    let draw = |rng: &mut Pcg32| -> Vec3 {
        let mut w = rng.upper_hemisphere();
        match rng.next_u32() % 3 {
            0 => w.z = [1e-6f32, 1e-9, 1e-20, 1e-38, 1e-44, 0.0][rng.next_u32() as usize % 6] * rng.next_f32(),
            1 => w.z = -w.z,
            _ => {}
        }
        let xy = (1.0 - w.z * w.z).max(0.0).sqrt() / w.truncate().length().max(1e-30);
        Vec3::new(w.x * xy, w.y * xy, w.z)
    };
    for (label, bsdf) in catalogue() {
        for _ in 0..1_000_000 {
            let (wi, wo) = (draw(&mut rng), draw(&mut rng));
            let f = bsdf.eval(wi, wo, [1.0, 0.5, 0.0]);
            let p = bsdf.pdf(wi, wo);
            assert!(
                f.iter().all(|x| x.is_finite() && *x >= 0.0) && p.is_finite() && p >= 0.0,
                "{label}: f={f:?} pdf={p} at {wi:?}, {wo:?}"
            );
            if wi.z <= 0.0 || wo.z <= 0.0 {
                assert!(f == [0.0; 3] && p == 0.0, "{label}: nonzero below the horizon at {wi:?}, {wo:?}");
            }
            if let Some(s) = bsdf.sample(wi, rng.next_vec2(), [1.0]) {
                assert!(
                    s.pdf > 0.0 && s.pdf.is_finite() && s.weight[0].is_finite() && s.wo.z >= 0.0,
                    "{label}: bad sample {s:?}"
                );
            } else {
                assert!(wi.z <= 0.0 || matches!(bsdf, DiffuseModel::Lambert(_)) || wi.z > 0.0, "{label}");
            }
        }
    }
}

#[test]
fn no_sample_from_below_the_surface() {
    let mut rng = Pcg32::new(5, 7);
    for (label, bsdf) in catalogue() {
        let wi = -rng.upper_hemisphere();
        assert!(bsdf.sample(wi, rng.next_vec2(), [0.5]).is_none(), "{label}");
    }
}
