//! The models' own importance samplers (`rust/brdf/src/cltc.rs`, `docs/sampling.md`): EON's
//! density against a second implementation in float64 (`sampling/eon_cltc.py`); for every
//! model with its own sampler (`DiffuseModel::own_sampler`), the density's integral over the
//! hemisphere, Mitsuba's chi-square test of the samples against it at several roughnesses and
//! incidences down to 89°, the cosine at roughness 0 and the per-lane kernel sampling as the
//! model. Finiteness, the weight `f cos/pdf` and the furnace hold for every model in
//! `properties.rs`.

#[path = "sampling/reference.rs"]
mod reference;

use crate::common::{catalogue, chi2_sampling, model, sidak};
use glam::Vec3;
use matte_brdf::{DiffuseBrdf, DiffuseModel, MODELS, ParamValue};
use std::f64::consts::PI;

fn direction(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// EON with its own sampler (the default is the cosine).
fn eon(r: f32) -> matte_brdf::DiffuseModel {
    model("eon", &[("roughness", &r.to_string()), ("sampling", "cltc")])
}

#[test]
fn eon_pdf_matches_the_float64_implementation() {
    let mut worst = 0.0f64;
    for &(r, ti, to, dphi, want) in &reference::EON_PDF {
        let wi = direction(ti, reference::AZIMUTH_I);
        let wo = direction(to, reference::AZIMUTH_I + dphi);
        let got = eon(r).pdf(wi, wo) as f64;
        let rel = (got - want).abs() / want;
        worst = worst.max(rel);
        assert!(rel <= 2e-5, "r={r} θi={ti} θo={to} Δφ={dphi}: pdf {got:.7e}, float64 {want:.7e}");
    }
    eprintln!("EON sampler density: largest relative difference to float64 {worst:.1e}");
}

/// `∫ pdf dω = 1` by a 1000 × 2000 midpoint rule in (cos θ, φ), for every model of the
/// catalogue (their own samplers or the cosine) at six incidences down to 89°.
#[test]
#[ignore = "thorough tier: `make test` runs it (cargo test -p matte-brdf -- --ignored)"]
fn every_density_integrates_to_one() {
    let (nz, nphi) = (1000usize, 2000usize);
    for (label, bsdf) in catalogue() {
        for ti in [0.0f32, 30.0, 60.0, 80.0, 85.0, 89.0] {
            let wi = direction(ti, 0.0);
            let mut sum = 0.0f64;
            for i in 0..nz {
                let z = (i as f64 + 0.5) / nz as f64;
                let s = (1.0 - z * z).sqrt();
                for j in 0..nphi {
                    let phi = (j as f64 + 0.5) / nphi as f64 * 2.0 * PI;
                    let wo = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32);
                    sum += bsdf.pdf(wi, wo) as f64;
                }
            }
            let integral = sum * (2.0 * PI) / (nz * nphi) as f64;
            assert!((integral - 1.0).abs() < 1e-3, "{label} θi={ti}: ∫ pdf = {integral:.6}");
        }
    }
}

/// The roughnesses the sampler tests sweep, in each model's own roughness parameter.
const ROUGHNESS: [&str; 4] = ["0.05", "0.3", "0.7", "1.0"];

/// Every model with its own sampler (its `sampling` parameter set to it), at each of [`ROUGHNESS`] (its first numeric parameter)
/// and each variant its examples declare (the other words and flags: Oren–Nayar's `model`,
/// van Ginneken's `shadowing`, roughdiffuse's `use_fast_approx`), its defaults otherwise.
fn own_samplers() -> Vec<(String, DiffuseModel)> {
    let mut out: Vec<(String, DiffuseModel)> = Vec::new();
    for spec in MODELS {
        let Some(roughness) = spec.numeric().next().map(|p| p.name) else { continue };
        let Some(own) = spec.own_sampler() else { continue };
        let mut variants: Vec<Vec<(&str, &str)>> = vec![vec![("sampling", own)]];
        for example in spec.examples {
            let mut words: Vec<(&str, &str)> =
                example.iter().copied().filter(|(n, _)| *n != roughness && *n != "sampling").collect();
            words.push(("sampling", own));
            if !variants.contains(&words) {
                variants.push(words);
            }
        }
        for words in &variants {
            for r in ROUGHNESS {
                let mut params = words.clone();
                params.push((roughness, r));
                let m = model(spec.name, &params);
                if m.own_sampler() {
                    out.push((format!("{} {params:?}", spec.name), m));
                }
            }
        }
    }
    out
}

#[test]
fn every_model_that_declares_its_own_sampler_draws_with_it() {
    let mut kinds: Vec<&str> = own_samplers().iter().map(|(_, m)| m.kind()).collect();
    kinds.dedup();
    let declared: Vec<&str> = MODELS.iter().filter(|s| s.own_sampler().is_some()).map(|s| s.name).collect();
    assert!(!declared.is_empty());
    assert_eq!(kinds, declared);
}

/// `∫ pdf dω = 1` (1000 × 2000 midpoint rule) for every own sampler at every roughness of
/// [`own_samplers`] and θi down to 89° (the catalogue's configurations are checked above).
#[test]
#[ignore = "thorough tier: `make test` runs it (cargo test -p matte-brdf -- --ignored)"]
fn every_own_sampler_integrates_to_one_at_every_roughness() {
    let (nz, nphi) = (500usize, 1000usize);
    for (label, bsdf) in own_samplers() {
        for ti in [0.0f32, 45.0, 80.0, 89.0] {
            let wi = direction(ti, 30.0);
            let mut sum = 0.0f64;
            for i in 0..nz {
                let z = (i as f64 + 0.5) / nz as f64;
                let s = (1.0 - z * z).sqrt();
                for j in 0..nphi {
                    let phi = (j as f64 + 0.5) / nphi as f64 * 2.0 * PI;
                    let wo = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32);
                    sum += bsdf.pdf(wi, wo) as f64;
                }
            }
            let integral = sum * (2.0 * PI) / (nz * nphi) as f64;
            assert!((integral - 1.0).abs() < 2e-3, "{label} θi={ti}: ∫ pdf = {integral:.6}");
        }
    }
}

#[test]
#[ignore = "thorough tier: `make test` runs it (cargo test -p matte-brdf -- --ignored)"]
fn every_own_sampler_passes_chi_square_at_every_roughness_and_down_to_89_degrees() {
    let angles = [0.0f32, 30.0, 60.0, 85.0, 89.0];
    let cases = own_samplers();
    let level = sidak(cases.len() * angles.len());
    let mut failures = vec![];
    for (i, (label, bsdf)) in cases.iter().enumerate() {
        for (j, &ti) in angles.iter().enumerate() {
            match chi2_sampling(bsdf, direction(ti, 0.0), 1000 + (i * 8 + j) as u64) {
                Ok(o) if o.p_value >= level => {}
                Ok(o) => failures
                    .push(format!("{label} θi={ti}: p = {:.3e} < {level:.3e} (χ² = {:.1})", o.p_value, o.statistic)),
                Err(e) => failures.push(format!("{label} θi={ti}: {e}")),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// At roughness 0 every fitted lobe is the identity with no uniform share: the sampler is the
/// cosine, density `cos θo / π` (van Ginneken's roughness is > 0: its sampler tends to the
/// cosine, checked at m = 10⁻⁶).
#[test]
fn every_own_sampler_is_the_cosine_at_roughness_zero() {
    for (label, m) in own_samplers() {
        let spec = m.spec();
        let roughness = spec.numeric().next().expect("a roughness").name;
        let zero = if spec.name == "ginneken" { "1e-6" } else { "0" };
        let words: Vec<(&str, String)> = m
            .parameters()
            .into_iter()
            .filter(|(n, _)| *n != roughness)
            .map(|(n, v)| match v {
                ParamValue::Number(x) => (n, x.to_string()),
                ParamValue::Flag(b) => (n, b.to_string()),
                ParamValue::Text(t) => (n, t),
                ParamValue::Texture { .. } => unreachable!("a model reports numbers, words and flags"),
            })
            .collect();
        let mut params: Vec<(&str, &str)> = words.iter().map(|(n, v)| (*n, v.as_str())).collect();
        params.push((roughness, zero));
        let m0 = model(spec.name, &params);
        for (ti, to, dphi) in [(0.0f32, 20.0f32, 0.0f32), (60.0, 45.0, 180.0), (85.0, 80.0, 90.0)] {
            let (wi, wo) = (direction(ti, 10.0), direction(to, 10.0 + dphi));
            let want = wo.z / std::f32::consts::PI;
            let got = m0.pdf(wi, wo);
            assert!((got - want).abs() <= 2e-6 * want, "{label} at roughness {zero}, θi={ti} θo={to}: {got} vs {want}");
        }
    }
}

/// At normal incidence Oren–Nayar's lobe is constant (the weight under the cosine is exact):
/// its fitted sampler is the cosine there at every roughness.
#[test]
fn oren_nayar_samplers_are_the_cosine_at_normal_incidence() {
    for (label, m) in own_samplers().into_iter().filter(|(_, m)| matches!(m.kind(), "oren_nayar" | "roughdiffuse")) {
        for (to, dphi) in [(20.0f32, 0.0f32), (75.0, 180.0), (89.0, 90.0)] {
            let wo = direction(to, dphi);
            let want = wo.z / std::f32::consts::PI;
            let got = m.pdf(Vec3::Z, wo);
            assert!((got - want).abs() <= 2e-6 * want, "{label} θo={to}: {got} vs {want}");
        }
    }
}

/// The per-lane kernel (textured parameters, the traced plugin) samples with the model's own
/// sampler: the same density and the same directions as the constant model.
#[test]
fn the_per_lane_kernel_samples_as_the_model() {
    use matte_brdf::kernel;
    for (label, bsdf) in catalogue() {
        let values: Vec<f32> = bsdf
            .parameters()
            .iter()
            .filter_map(|(name, v)| match v {
                matte_brdf::ParamValue::Number(x) if bsdf.spec().numeric().any(|p| p.name == *name) => Some(*x as f32),
                _ => None,
            })
            .collect();
        let Some(lane) = bsdf.lane_kernel_f32(&values) else { panic!("{label}: no lane kernel for {values:?}") };
        for (ti, to, dphi) in [(30.0f32, 60.0f32, 180.0f32), (85.0, 20.0, 0.0), (60.0, 88.0, 90.0)] {
            let (wi, wo) = (direction(ti, 0.0), direction(to, dphi));
            let (a, b) = (bsdf.pdf(wi, wo), kernel::pdf(&lane, wi.into(), wo.into()));
            assert!((a - b).abs() <= 1e-5 * a, "{label} θi={ti}: model pdf {a}, lane pdf {b}");
            let s = bsdf.sample(wi, glam::Vec2::new(0.37, 0.81), [1.0]).expect("a sample");
            let (w, _, p) = kernel::sample(&lane, wi.into(), 0.37, 0.81, [1.0f32]);
            assert!(
                (Vec3::from(w) - s.wo).length() <= 1e-5 && (p - s.pdf).abs() <= 1e-5 * p,
                "{label}: lane sample differs"
            );
        }
    }
}
