//! The f32 per-eval kernels against the same models evaluated independently in f64 with `std`
//! trigonometry (the published forms, written out here: angles from `acos`/`atan2`, Fresnel
//! from Snell's law, hemispherical Fresnel averages by a midpoint rule). The kernels use
//! polynomial `acos`/`atan`, rearranged Fresnel terms and reciprocals formed in `new()`; this
//! checks that what remains is f32 rounding: the stated bounds are relative errors, with an
//! absolute floor (a fraction of ρ/π) where a model's value passes through zero or its terms
//! cancel. The largest errors are where f32 inputs cancel, which the kernels always had: EON's
//! `1 + r s/t` at Δφ = π and grazing (rounding `s` alone is 1.4e-5 of it), full Oren–Nayar's
//! `C1 + cos Δφ C2 tan β` in forward-grazing configurations.

use crate::common::{Pcg32, PcgExt, model};
use glam::{DVec3, Vec3};
use matte_brdf::{DiffuseBrdf, DiffuseModel};
use std::f64::consts::{FRAC_PI_2, PI};

const RHO: [f32; 3] = [0.8, 0.5, 0.2];

/// Random direction pairs on the upper hemisphere, cosines from 1e-3 up, plus a few exact
/// configurations (normal incidence, equal angles, Δφ = 0 and π).
fn pairs() -> Vec<(Vec3, Vec3)> {
    let mut rng = Pcg32::new(7, 11);
    let mut out: Vec<(Vec3, Vec3)> = (0..20_000)
        .map(|_| (rng.upper_hemisphere(), rng.upper_hemisphere()))
        .filter(|(a, b)| a.z >= 1e-3 && b.z >= 1e-3)
        .collect();
    let dir = |t: f32, p: f32| Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
    for (ti, to, dp) in
        [(0.0f32, 0.0f32, 0.0f32), (0.5, 0.5, 0.0), (1.2, 1.2, std::f32::consts::PI), (1.5, 0.3, 1.0), (0.3, 1.5, 2.0)]
    {
        out.push((dir(ti, 0.2), dir(to, 0.2 + dp)));
    }
    out
}

/// Max over all pairs and channels of |f32 − f64| / max(|f64|, floor · ρ/π).
fn max_relative_error(
    bsdf: &DiffuseModel,
    floor: f64,
    oracle: impl Fn(DVec3, DVec3, f64) -> f64,
) -> (f64, (Vec3, Vec3)) {
    let mut worst = (0.0, (Vec3::Z, Vec3::Z));
    for (wi, wo) in pairs() {
        let got = bsdf.eval(wi, wo, RHO);
        for (k, &rho) in RHO.iter().enumerate() {
            let want = oracle(wi.as_dvec3(), wo.as_dvec3(), rho as f64);
            let err = (got[k] as f64 - want).abs() / want.abs().max(floor * rho as f64 / PI);
            if err > worst.0 {
                worst = (err, (wi, wo));
            }
        }
    }
    worst
}

/// Polar angle and azimuth of a direction.
fn angles(w: DVec3) -> (f64, f64) {
    (w.z.clamp(-1.0, 1.0).acos(), w.y.atan2(w.x))
}

/// cos Δφ from the two azimuths (0 when an azimuth is undefined, as the full O–N model).
fn cos_delta_phi(wi: DVec3, wo: DVec3) -> f64 {
    if wi.truncate().length() < 1e-12 || wo.truncate().length() < 1e-12 {
        return 0.0;
    }
    (angles(wo).1 - angles(wi).1).cos()
}

#[test]
fn oren_nayar_qualitative_matches_the_trigonometric_form() {
    for sigma in [0.1f64, 0.3, 1.0] {
        let bsdf = model("oren_nayar", &[("sigma", &sigma.to_string())]);
        let s2 = sigma * sigma;
        let (a, b) = (1.0 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09));
        let (err, at) = max_relative_error(&bsdf, 1e-6, |wi, wo, rho| {
            let (ti, to) = (angles(wi).0, angles(wo).0);
            let (alpha, beta) = (ti.max(to), ti.min(to));
            rho / PI * (a + b * cos_delta_phi(wi, wo).max(0.0) * alpha.sin() * beta.tan())
        });
        assert!(err <= 1e-6, "σ = {sigma}: relative error {err:e} at {at:?}");
    }
}

#[test]
fn oren_nayar_full_matches_the_trigonometric_form() {
    for sigma in [0.1f64, 0.3, 1.0] {
        let bsdf = model("oren_nayar", &[("sigma", &sigma.to_string()), ("model", "full")]);
        let s2 = sigma * sigma;
        // Relative to max(f, ρ/π): the terms are each of order ρ/π and cancel to ~1e-3 of it
        // in forward-grazing configurations (where the value is then clamped at 0).
        let (err, at) = max_relative_error(&bsdf, 1.0, |wi, wo, rho| {
            let (ti, to) = (angles(wi).0, angles(wo).0);
            let (alpha, beta) = (ti.max(to), ti.min(to));
            let cp = cos_delta_phi(wi, wo);
            let c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
            let tb = 2.0 * beta / PI;
            let c2 = 0.45 * s2 / (s2 + 0.09) * if cp >= 0.0 { alpha.sin() } else { alpha.sin() - tb.powi(3) };
            let c3 = 0.125 * s2 / (s2 + 0.09) * (4.0 * alpha * beta / (PI * PI)).powi(2);
            let direct = c1 + cp * c2 * beta.tan() + (1.0 - cp.abs()) * c3 * ((alpha + beta) / 2.0).tan();
            let inter = 0.17 * s2 / (s2 + 0.13) * (1.0 - cp * tb * tb);
            (rho / PI * (direct + rho * inter)).max(0.0)
        });
        assert!(err <= 2e-5, "σ = {sigma}: relative error {err:e} at {at:?}");
    }
}

/// Fujii's azimuth-integrated term with its original `S/μ` form (JCGT 14(1) 2025).
fn fon_g(mu: f64) -> f64 {
    let s = (1.0 - mu * mu).sqrt();
    s * (mu.acos() - s * mu) + 2.0 / 3.0 * ((s / mu) * (1.0 - s.powi(3)) - s)
}

#[test]
fn eon_matches_the_f64_closed_form() {
    for r in [0.05f64, 0.3, 0.7, 1.0] {
        let bsdf = model("eon", &[("roughness", &r.to_string())]);
        let a_f = 1.0 / (1.0 + (0.5 - 2.0 / (3.0 * PI)) * r);
        let b_f = r * a_f;
        let e_avg = a_f * (1.0 + (2.0 / 3.0 - 28.0 / (15.0 * PI)) * r);
        let e_f = |mu: f64| a_f + b_f / PI * fon_g(mu);
        let (err, at) = max_relative_error(&bsdf, 1e-6, |wi, wo, rho| {
            let s = wi.x * wo.x + wi.y * wo.y;
            let s_over_t = if s > 0.0 { s / wi.z.max(wo.z) } else { s };
            let single = rho / PI * a_f * (1.0 + r * s_over_t);
            let rho_ms = rho * rho * e_avg / (1.0 - rho * (1.0 - e_avg));
            let multi = rho_ms / PI * (1.0 - e_f(wi.z)) * (1.0 - e_f(wo.z)) / (1.0 - e_avg);
            single + multi
        });
        assert!(err <= 2e-5, "r = {r}: relative error {err:e} at {at:?}");
    }
}

/// Unpolarised Fresnel reflectance by Snell's law and the s/p amplitudes, light arriving at
/// `cos θ = c` onto relative index `n` (total internal reflection gives 1).
fn fresnel_snell(c: f64, n: f64) -> f64 {
    let sin_t2 = (1.0 - c * c) / (n * n);
    if sin_t2 >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - sin_t2).sqrt();
    let rs = (c - n * ct) / (c + n * ct);
    let rp = (n * c - ct) / (n * c + ct);
    0.5 * (rs * rs + rp * rp)
}

/// `2 ∫₀¹ F(μ, n) μ dμ` by the midpoint rule (split at the critical cosine for n < 1).
fn fresnel_average(n: f64) -> f64 {
    let mu_c = if n < 1.0 { (1.0 - n * n).sqrt() } else { 0.0 };
    let steps = 400_000;
    let h = (1.0 - mu_c) / steps as f64;
    let upper: f64 =
        (0..steps).map(|k| mu_c + (k as f64 + 0.5) * h).map(|mu| 2.0 * fresnel_snell(mu, n) * mu * h).sum();
    mu_c * mu_c + upper
}

#[test]
fn wolff_matches_snell_fresnel_in_f64() {
    for (int_ior, ext_ior) in [(1.4f64, 1.0f64), (1.5046, 1.0), (2.419, 1.333), (1.0001, 1.0)] {
        let n = int_ior / ext_ior;
        let f0 = ((n - 1.0) / (n + 1.0)).powi(2);
        let (f_ext, f_int) = (fresnel_average(n), fresnel_average(1.0 / n));
        for norm in ["physical", "normal", "raw"] {
            let bsdf = model(
                "wolff",
                &[("int_ior", &int_ior.to_string()), ("ext_ior", &ext_ior.to_string()), ("normalization", norm)],
            );
            let k = |rho: f64| match norm {
                "raw" => rho / PI,
                "normal" => rho / (PI * (1.0 - f0) * (1.0 - f_ext)),
                _ => rho / (PI * n * n * (1.0 - rho * f_int)),
            };
            let (err, at) = max_relative_error(&bsdf, 1e-6, |wi, wo, rho| {
                k(rho) * (1.0 - fresnel_snell(wi.z, n)) * (1.0 - fresnel_snell(wo.z, n))
            });
            assert!(err <= 1e-6, "n = {n} {norm}: relative error {err:e} at {at:?}");
        }
    }
}

#[test]
fn reference_helpers_are_sane() {
    // The oracles above must themselves be right: Fresnel at normal incidence and the known
    // hemispherical average for n = 1.5 (`docs/models.md#fresnel`), and G at the end points.
    assert!((fresnel_snell(1.0, 1.5) - 0.04).abs() < 1e-12);
    assert!((fresnel_average(1.5) - 0.09178).abs() < 1e-5);
    assert!((fon_g(1.0) - 0.0).abs() < 1e-12);
    assert!((fon_g(1e-9) - (FRAC_PI_2 - 2.0 / 3.0)).abs() < 1e-6);
}
