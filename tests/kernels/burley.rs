//! Burley's diffuse (`burley`): the kernel against Burley's 2012 formula written the original
//! way, in f64 — `f = ρ/π (1 + (F_D90 − 1)(1 − μi)⁵)(1 + (F_D90 − 1)(1 − μo)⁵)` with
//! `F_D90 = 1/2 + 2 r cos²θd` and θd from the normalised half vector — which expands to the
//! diffuse-plus-retro-reflection split the kernel (and Mitsuba's `principled`) evaluates.
//! Reciprocity, sampling (χ²), furnace, finiteness, ranges, lane clamps and textures are the
//! registry-wide tests' (tests/kernels/properties.rs, tests/kernels/chi_square.rs, tests/kernels/registry.rs), which
//! include every registered model.

use crate::common::{Pcg32, PcgExt};
use glam::DVec3;
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue, Params};

fn burley(r: f64) -> DiffuseModel {
    DiffuseModel::from_params("burley", Params::new().with("roughness", ParamValue::Number(r))).unwrap()
}

/// Burley 2012, eq. in §5.3, in f64.
fn published(r: f64, rho: f64, wi: DVec3, wo: DVec3) -> f64 {
    let h = (wi + wo).normalize();
    let cos_d = h.dot(wi);
    let f_d90 = 0.5 + 2.0 * r * cos_d * cos_d;
    let term = |mu: f64| 1.0 + (f_d90 - 1.0) * (1.0 - mu).powi(5);
    rho / std::f64::consts::PI * term(wi.z) * term(wo.z)
}

#[test]
fn eval_is_the_published_formula() {
    let mut rng = Pcg32::new(11, 3);
    for r in [0.0, 0.25, 0.5, 1.0] {
        let m = burley(r);
        let mut worst = 0.0f64;
        for _ in 0..20_000 {
            let (wi, wo) = (rng.upper_hemisphere(), rng.upper_hemisphere());
            if wi.z <= 0.0 || wo.z <= 0.0 {
                continue; // one-sided: 0 on the horizon, which the formula does not know
            }
            let got = m.eval(wi, wo, [0.7])[0] as f64;
            let want = published(r, 0.7, wi.as_dvec3(), wo.as_dvec3());
            worst = worst.max((got - want).abs() / want);
        }
        assert!(worst < 2e-6, "roughness {r}: relative error {worst:.2e}");
    }
}

#[test]
fn normal_incidence_and_grazing_limits() {
    // Both at the normal: F = 0, f = ρ/π for every roughness.
    let n = glam::Vec3::Z;
    for r in [0.0, 0.5, 1.0] {
        let f = burley(r).eval(n, n, [1.0])[0];
        assert!((f - std::f32::consts::FRAC_1_PI).abs() < 1e-7, "r = {r}: {f}");
    }
    // Retro-reflection at grazing (wi = wo, μ → 0): (1 + (F_D90 − 1))² = F_D90² = (1/2 + 2r)².
    let g = glam::Vec3::new(1.0, 0.0, 1e-6).normalize();
    for r in [0.0f32, 0.5, 1.0] {
        let f = burley(r as f64).eval(g, g, [1.0])[0] * std::f32::consts::PI;
        let want = (0.5 + 2.0 * r) * (0.5 + 2.0 * r);
        assert!((f - want).abs() < 1e-4 * want, "r = {r}: {f} vs {want}");
    }
}

#[test]
fn defaults_and_errors() {
    let m = DiffuseModel::from_params("burley", Params::new()).unwrap();
    assert_eq!(
        m.parameters(),
        vec![("roughness", ParamValue::Number(0.5)), ("sampling", ParamValue::Text("cosine".into()))]
    );
    for bad in [-0.1, 1.1, f64::NAN] {
        let e = DiffuseModel::from_params("burley", Params::new().with("roughness", ParamValue::Number(bad)))
            .expect_err("out of range");
        assert_eq!(e.param, "roughness");
    }
}
