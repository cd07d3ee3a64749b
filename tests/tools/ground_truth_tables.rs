//! The ground-truth tables the repository ships (`python/matte_mitsuba/ground_truth/`, `make ground-truth`;
//! `docs/microgeometry.md#the-tabulated-ground-truth-brdf`), read as they are, without
//! simulating: both surfaces at every documented roughness, each loading in `matte render` on the
//! nodes `matte microgeometry --table` writes, reciprocal within its intervals, with a white
//! albedo of 1 (the furnace) and no E/ρ above 1; and both surfaces' retro-reflection growing
//! with their roughness.

use glam::{Vec2, Vec3};
use matte_brdf::DiffuseBrdf;
use matte_brdf::DiffuseModel;
use matte_brdf::tabulated::BrdfTable;
use matte_brdf::tabulated::{TABLE_DELTA_PHI, TABLE_REFLECTANCE, TABLE_THETA};
use matte_render::bsdf::{Bsdf, Bxdf, Matte};
use matte_render::load::load_str;
use matte_render::shape::SurfaceInteraction;
use std::path::PathBuf;

/// The roughness values of both surfaces (`validation/generators/ground_truth_tables.sh`).
const ROUGHNESS: [&str; 6] = ["0.1", "0.2", "0.3", "0.5", "0.7", "1.0"];

fn folder() -> PathBuf {
    crate::common::repo().join("python/matte_mitsuba/ground_truth")
}

fn v_cavities(s: &str) -> String {
    format!("v_cavities_sigma{s}.json")
}

fn height_field(s: &str) -> String {
    format!("height_field_m{s}.json")
}

fn direction(theta_deg: f64, phi_deg: f64) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new((t.sin() * p.cos()) as f32, (t.sin() * p.sin()) as f32, t.cos() as f32)
}

/// `f/ρ` and its half-width on nodes (reflectance r, θi i, θo o, Δφ p).
fn node(t: &BrdfTable, r: usize, i: usize, o: usize, p: usize) -> (f32, f32) {
    let (nt, np) = (t.theta_deg.len(), t.delta_phi_deg.len());
    let k = ((r * nt + i) * nt + o) * np + p;
    (t.f_over_reflectance[k], t.half_width_over_reflectance[k])
}

#[test]
fn every_table_loads_on_the_documented_nodes_reciprocal_and_energy_conserving() {
    let mut have: Vec<String> = std::fs::read_dir(folder())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json"))
        .collect();
    have.sort();
    let mut want: Vec<String> = ROUGHNESS.iter().flat_map(|s| [v_cavities(s), height_field(s)]).collect();
    want.sort();
    assert_eq!(have, want, "the tables in python/matte_mitsuba/ground_truth/");
    for s in ROUGHNESS {
        for (name, what) in [
            (v_cavities(s), format!("V-cavities, sigma = {} rad,", s.parse::<f64>().unwrap())),
            (height_field(s), format!("Gaussian height field, m = {},", s.parse::<f64>().unwrap())),
        ] {
            let path = folder().join(&name);
            // As a scene uses it: matte render's loader.
            let xml = format!(
                "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n<bsdf type=\"tabulated_brdf\">\n\
                 <string name=\"filename\" value=\"{}\"/>\n<rgb name=\"reflectance\" value=\"0.2, 0.5, 1\"/></bsdf>\n</scene>",
                path.display()
            );
            let scene = load_str(&xml, &folder().join("scene.xml"), &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
            let bsdf = &scene.scene.bsdfs[0];
            let Bsdf::Matte(Matte { model: DiffuseModel::Tabulated(table), .. }) = bsdf else {
                panic!("{name}: {bsdf:?}")
            };
            let t = table.table();
            assert!(t.description.starts_with(&what), "{name}: {}", t.description);
            assert_eq!(
                (&t.theta_deg[..], &t.delta_phi_deg[..], &t.reflectance[..]),
                (&TABLE_THETA[..], &TABLE_DELTA_PHI[..], &TABLE_REFLECTANCE[..]),
                "{name}"
            );
            assert_eq!(t.half_width_over_reflectance.len(), t.f_over_reflectance.len(), "{name}: no intervals");
            // The renderer's f32 kernel is the file's interpolation.
            let (wi, wo) = (direction(60.0, 0.0), direction(35.0, 150.0));
            let (f_cos, _) = bsdf.eval_pdf(&SurfaceInteraction::at_uv(Vec2::ZERO), wi, wo);
            for (c, rho) in [0.2f32, 0.5, 1.0].into_iter().enumerate() {
                let want = t.eval_angles(60.0, 35.0, 150.0, rho);
                assert!(
                    (f_cos[c] / wo.z / want - 1.0).abs() < 1e-4,
                    "{name}: channel {c}: {} vs {want}",
                    f_cos[c] / wo.z
                );
            }
            // Reciprocal: f(θi, θo) and f(θo, θi) within their intervals.
            let (nr, nt, np) = (t.reflectance.len(), t.theta_deg.len(), t.delta_phi_deg.len());
            for r in 0..nr {
                for i in 0..nt {
                    for o in 0..i {
                        for p in 0..np {
                            let ((a, ha), (b, hb)) = (node(t, r, i, o, p), node(t, r, o, i, p));
                            assert!(a > 0.0 && (a - b).abs() <= ha + hb, "{name}: ({r}, {i}, {o}, {p}): {a} vs {b}");
                        }
                    }
                }
            }
            // Energy: no E/ρ above 1, and the white surface returns everything (the furnace).
            let worst = t.max_albedo_over_reflectance();
            assert!(worst <= 1.0 + 1e-4, "{name}: E/rho up to {worst}");
            for &theta in &t.theta_deg {
                let e = t.albedo(theta.to_radians().cos(), 1.0).value;
                assert!((e - 1.0).abs() <= 2e-3, "{name}: white albedo {e} at theta_i = {theta}");
            }
        }
    }
}

/// At ρ = 1, f(θi = θo = 60°) toward the source (Δφ = 0) over the same away from it
/// (Δφ = 180°).
fn retro_over_forward(t: &BrdfTable) -> f32 {
    let rho = 1.0;
    t.eval_angles(60.0, 60.0, 0.0, rho) / t.eval_angles(60.0, 60.0, 180.0, rho)
}

#[test]
fn rougher_surfaces_reflect_more_toward_the_source() {
    for (surface, file) in [("V-cavities", v_cavities as fn(&str) -> String), ("height field", height_field)] {
        let ratios: Vec<f32> =
            ROUGHNESS.iter().map(|s| retro_over_forward(&BrdfTable::read(&folder().join(file(s))).unwrap())).collect();
        assert!(ratios[0] > 1.0, "{surface}: {ratios:?}");
        assert!(ratios.windows(2).all(|w| w[1] > w[0]), "{surface}: not increasing with {ROUGHNESS:?}: {ratios:?}");
    }
}
