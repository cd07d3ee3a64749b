//! The tabulated BRDF (`docs/microgeometry.md#the-tabulated-ground-truth-brdf`) against closed
//! forms: a table of full Oren–Nayar on the grid `matte microgeometry --table` uses reproduces
//! the model within the interpolation error stated in the doc, its albedo within the same, a
//! table of EON keeps a white surface's energy, the cosine sampling passes Mitsuba's chi-square
//! test and its pdf integrates to 1, and files round-trip or fail with a clear message.

use crate::common::{Pcg32, PcgExt, chi2_sampling, direction, model, sidak, table_of};
use glam::Vec3;
use matte_brdf::tabulated::{BrdfTable, Tabulated};
use matte_brdf::tabulated::{TABLE_DELTA_PHI, TABLE_REFLECTANCE, TABLE_THETA};
use matte_brdf::{DiffuseBrdf, DiffuseModel};
use std::f64::consts::PI;

/// Relative error of the table against the model at random directions with θ ≤ `max_theta`°
/// and random ρ: (mean, largest).
fn interpolation_error(m: &DiffuseModel, t: &BrdfTable, max_theta: f64) -> (f64, f64) {
    let mut rng = Pcg32::new(3, 1);
    let (mut sum, mut worst, n) = (0.0f64, 0.0f64, 20_000);
    for _ in 0..n {
        let mut dir = || {
            let theta = (rng.next_f64() * max_theta).to_radians();
            direction(theta, rng.next_f64() * 2.0 * PI)
        };
        let (wi, wo) = (dir(), dir());
        let rho = 0.05 + 0.95 * rng.next_f32();
        let (a, b) = (t.eval(wi, wo, [rho])[0] as f64, m.eval(wi, wo, [rho])[0] as f64);
        let e = (a / b - 1.0).abs();
        sum += e;
        worst = worst.max(e);
    }
    (sum / n as f64, worst)
}

#[test]
fn a_table_of_oren_nayar_reproduces_it_within_the_interpolation_error() {
    let m = model("oren_nayar", &[("sigma", "0.3"), ("model", "full")]);
    let t = table_of(&m);
    // Exact on the nodes.
    for (ti, to, dp) in [(30.0f64, 60.0f64, 0.0f64), (80.0, 10.0, 180.0), (0.0, 50.0, 90.0)] {
        let (wi, wo) = (direction(ti.to_radians(), 0.0), direction(to.to_radians(), dp.to_radians()));
        let (a, b) = (t.eval(wi, wo, [0.5])[0], m.eval(wi, wo, [0.5])[0]);
        assert!((a / b - 1.0).abs() < 1e-4, "node ({ti}, {to}, {dp}): table {a}, model {b}");
    }
    // Between nodes: the error the doc states (mean 0.17 %, largest 4 % up to 80°).
    let (mean, worst) = interpolation_error(&m, &t, 80.0);
    assert!(mean < 0.003 && worst < 0.05, "mean {mean}, largest {worst}");
}

#[test]
fn a_table_keeps_the_models_albedo_and_a_white_surfaces_energy() {
    let on = model("oren_nayar", &[("sigma", "0.3"), ("model", "full")]);
    let t = table_of(&on);
    for deg in [0.0f64, 30.0, 60.0, 80.0] {
        let mu = deg.to_radians().cos();
        let (a, b) = (t.albedo(mu, 0.8).value, on.albedo(mu, 0.8).value);
        assert!((a / b - 1.0).abs() < 0.01, "θi = {deg}: table {a}, model {b}");
    }
    let eon = model("eon", &[("roughness", "0.6")]);
    let t = table_of(&eon);
    // A white EON surface reflects everything; the table's interpolation toward grazing adds
    // up to 1.5 % (at θi = 89°, the doc's stated bound).
    for deg in [0.0f64, 45.0, 70.0, 85.0, 89.0] {
        let e = t.albedo(deg.to_radians().cos(), 1.0).value;
        assert!(e <= 1.02 && e > 0.98, "θi = {deg}: white albedo {e}");
    }
    assert!(t.max_albedo_over_reflectance() <= 1.02);
}

#[test]
fn sampling_passes_the_chi_square_test_and_its_pdf_integrates_to_one() {
    let t = table_of(&model("oren_nayar", &[("sigma", "0.5")]));
    for (k, deg) in [0.0f32, 45.0, 80.0].iter().enumerate() {
        let wi = Vec3::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
        let o = chi2_sampling(&t, wi, 40 + k as u64).unwrap();
        assert!(o.p_value >= sidak(3), "θi = {deg}: p = {}", o.p_value);
        // ∫ pdf dω over the sphere by the midpoint rule in (cos θ, φ).
        let n = 400;
        let mut integral = 0.0;
        for i in 0..n {
            let mu = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
            for j in 0..n {
                let phi = 2.0 * PI * (j as f64 + 0.5) / n as f64;
                integral += t.pdf(wi, direction(mu.acos(), phi)) as f64;
            }
        }
        integral *= 4.0 * PI / (n * n) as f64;
        assert!((integral - 1.0).abs() < 1e-3, "θi = {deg}: ∫ pdf = {integral}");
    }
}

#[test]
fn files_round_trip_and_bad_files_give_one_line_errors() {
    let t = table_of(&model("oren_nayar", &[("sigma", "0.3")]));
    let dir = std::env::temp_dir().join(format!("matte_tabulated_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("t.json");
    t.write(&path).unwrap();
    let back = BrdfTable::read(&path).unwrap();
    assert_eq!(back.f_over_reflectance, t.f_over_reflectance);

    let missing = BrdfTable::read(&dir.join("missing.json")).unwrap_err();
    assert!(missing.contains("missing.json"), "{missing}");
    std::fs::write(&path, "{\"format\": \"matte-tabulated-brdf\",\n \"version\": 1,\n \"oops\"").unwrap();
    let broken = BrdfTable::read(&path).unwrap_err();
    assert!(broken.contains("t.json:3"), "{broken}");
    let mut short = t.clone();
    short.f_over_reflectance.pop();
    std::fs::write(&path, serde_json::to_string(&short).unwrap()).unwrap();
    let e = BrdfTable::read(&path).unwrap_err();
    assert!(e.contains("f_over_reflectance") && !e.contains('\n'), "{e}");
    let mut nan = t.clone();
    nan.theta_deg[3] = 95.0;
    std::fs::write(&path, serde_json::to_string(&nan).unwrap()).unwrap();
    assert!(BrdfTable::read(&path).unwrap_err().contains("theta_deg"));
    std::fs::remove_dir_all(&dir).ok();
}

/// A table of positive pseudo-random values (no smoothness for the interpolation to hide
/// behind) on the given nodes.
fn noise_table(theta: Vec<f64>, delta_phi: Vec<f64>, reflectance: Vec<f64>, seed: u64) -> BrdfTable {
    let mut rng = Pcg32::new(seed, 5);
    let n = theta.len().pow(2) * delta_phi.len() * reflectance.len();
    let values = (0..n).map(|_| 0.05 + rng.next_f32()).collect();
    BrdfTable::new("noise", theta, delta_phi, reflectance, values, Vec::new()).unwrap()
}

/// The kernel the renderer and the plugin run (`Tabulated`: polynomial acos/atan2, branch-free
/// cell location, gathers) equals the table's own interpolation (`BrdfTable::eval_angles`:
/// f64 angles, nodes found by search) to float precision, on random directions over the whole
/// hemisphere (beyond the last θ node too) and reflectances beyond both ends, for the
/// production grid, a noisy table and tables with single-node axes. The difference is measured
/// against ρ times the table's largest value: the f32 angles' error (an ulp of the direction,
/// the 3.5e-7 of the polynomial acos) moves the weights by a few 1e-6 of a cell, which changes
/// the value by that fraction of the cell's spread, not of its (possibly small) value. A
/// channel evaluated alone (its own two reflectance nodes) equals it evaluated with two others
/// (every node gathered once for all three).
#[test]
fn the_kernel_is_the_tables_own_interpolation() {
    let tables = [
        ("oren_nayar", table_of(&model("oren_nayar", &[("sigma", "0.3"), ("model", "full")]))),
        ("noise", noise_table(TABLE_THETA.to_vec(), TABLE_DELTA_PHI.to_vec(), TABLE_REFLECTANCE.to_vec(), 7)),
        ("uneven", noise_table(vec![5.0, 7.0, 30.0, 60.0, 88.0], vec![10.0, 170.0], vec![0.2, 0.3, 0.9], 8)),
        ("single nodes", noise_table(vec![0.0, 45.0, 80.0], vec![0.0], vec![0.5], 9)),
    ];
    let mut rng = Pcg32::new(21, 3);
    for (name, t) in tables {
        let k = Tabulated::new(t.clone());
        let scale = t.f_over_reflectance.iter().fold(0.0f64, |m, &v| m.max(v as f64));
        let mut worst = 0.0f64;
        for _ in 0..50_000 {
            let mut dir = || {
                let mu = rng.next_f64();
                direction(mu.acos(), rng.next_f64() * 2.0 * PI)
            };
            let (wi, wo) = (dir(), dir());
            let rho = [-0.1 + 1.2 * rng.next_f32(), rng.next_f32(), 0.5];
            let (a, b) = (k.eval(wi, wo, rho), t.eval(wi, wo, rho));
            for c in 0..3 {
                // One channel gathers at its two reflectance nodes, three share every node's
                // packet (fewer than six): the same arithmetic, so the same value.
                assert_eq!(k.eval(wi, wo, [rho[c]])[0], a[c], "{name}: one channel against three");
                let e = (a[c] as f64 - b[c] as f64).abs() / (scale * (rho[c].abs() as f64).max(1e-3));
                assert!(e < 1e-5, "{name}: wi {wi}, wo {wo}, ρ {}: kernel {}, table {}", rho[c], a[c], b[c]);
                worst = worst.max(e);
            }
        }
        eprintln!("{name}: largest relative difference {worst:.2e}");
        // Exactly the node value on a node (ρ on a node, directions on nodes).
        let (ti, to, dp) = (t.theta_deg[1], t.theta_deg[0], t.delta_phi_deg[0]);
        let (wi, wo) = (direction(ti.to_radians(), 0.0), direction(to.to_radians(), dp.to_radians()));
        let rho = t.reflectance[0].max(0.25) as f32;
        let node = t.eval_angles(ti, to, dp, rho) as f64;
        assert!((k.eval(wi, wo, [rho])[0] as f64 / node - 1.0).abs() < 2e-5, "{name} at a node");
    }
}
