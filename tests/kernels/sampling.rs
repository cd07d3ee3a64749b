//! The models' own importance samplers (`rust/brdf/cltc.rs`, `docs/sampling.md`): the
//! density against a second implementation in float64 (`sampling/eon_cltc.py`), its integral
//! over the hemisphere, Mitsuba's chi-square test of the samples against it at several
//! roughnesses and incidences down to 89°, and the cosine at roughness 0. Finiteness, the
//! weight `f cos/pdf` and the furnace hold for every model in `properties.rs`.

#[path = "sampling/reference.rs"]
mod reference;

use crate::common::{catalogue, chi2_sampling, model, sidak};
use glam::Vec3;
use matte::brdf::DiffuseBrdf;
use std::f64::consts::PI;

fn direction(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// EON with its own sampler (the default is the cosine).
fn eon(r: f32) -> matte::brdf::DiffuseModel {
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

#[test]
fn eon_sampler_passes_chi_square_at_every_roughness_and_down_to_89_degrees() {
    let roughness = [0.05f32, 0.3, 0.7, 1.0];
    let angles = [0.0f32, 30.0, 60.0, 85.0, 89.0];
    let level = sidak(roughness.len() * angles.len());
    let mut failures = vec![];
    for (i, &r) in roughness.iter().enumerate() {
        for (j, &ti) in angles.iter().enumerate() {
            match chi2_sampling(&eon(r), direction(ti, 0.0), 1000 + (i * 8 + j) as u64) {
                Ok(o) if o.p_value >= level => {}
                Ok(o) => failures
                    .push(format!("r={r} θi={ti}: p = {:.3e} < {level:.3e} (χ² = {:.1})", o.p_value, o.statistic)),
                Err(e) => failures.push(format!("r={r} θi={ti}: {e}")),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// At roughness 0 the lobe is the identity and the uniform probability 0: the sampler is
/// the cosine, density `cos θo / π`.
#[test]
fn eon_sampler_is_the_cosine_at_roughness_zero() {
    let m = eon(0.0);
    for (ti, to, dphi) in [(0.0f32, 20.0f32, 0.0f32), (60.0, 45.0, 180.0), (85.0, 80.0, 90.0)] {
        let (wi, wo) = (direction(ti, 10.0), direction(to, 10.0 + dphi));
        let want = wo.z / std::f32::consts::PI;
        assert!((m.pdf(wi, wo) - want).abs() <= 1e-6 * want, "θi={ti} θo={to}: {} vs {want}", m.pdf(wi, wo));
    }
}

/// The per-lane kernel (textured parameters, the traced plugin) samples with the model's own
/// sampler: the same density and the same directions as the constant model.
#[test]
fn the_per_lane_kernel_samples_as_the_model() {
    use matte::brdf::kernel;
    for (label, bsdf) in catalogue() {
        let values: Vec<f32> = bsdf
            .parameters()
            .iter()
            .filter_map(|(name, v)| match v {
                matte::brdf::ParamValue::Number(x) if bsdf.spec().numeric().any(|p| p.name == *name) => Some(*x as f32),
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
