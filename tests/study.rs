//! `matte study` plumbing: statistics helpers against closed forms, and a tiny end-to-end
//! run (its numbers are the study's business; here: Lambert's ratio to itself is exactly 1,
//! intervals are finite, and every file the report names exists).

use matte::study::metrics::{edge_vs_flat, mean_ci99};
use std::process::Command;

#[test]
fn mean_ci99_matches_the_t_quantile() {
    // Sample 1, 2, 3, 4: mean 2.5, s² = 5/3, se = sqrt(5/12); t(3) 0.995 quantile = 5.840909.
    let (m, hw) = mean_ci99(&[1.0, 2.0, 3.0, 4.0]);
    assert!((m - 2.5).abs() < 1e-12);
    assert!((hw - 5.840909 * (5.0f64 / 12.0).sqrt()).abs() < 1e-5, "half-width {hw}");
}

#[test]
fn edge_vs_flat_averages_absolute_values_by_region() {
    let rel = [0.1f32, -0.3, f32::NAN, 0.2, -0.2];
    let edges = [true, true, true, false, false];
    let (e, f) = edge_vs_flat(&rel, &edges);
    assert!((e - 0.2).abs() < 1e-6 && (f - 0.2).abs() < 1e-6, "{e} {f}");
}

#[test]
fn study_run_writes_strips_report_and_sane_numbers() {
    let out = std::env::temp_dir().join(format!("matte_study_test_{}", std::process::id()));
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/mitsuba_scenes/sphere_lambert.xml");
    let o = Command::new(env!("CARGO_BIN_EXE_matte"))
        .args(["study", scene, "--spp", "8", "--passes", "4", "--res", "24", "-q", "-o"])
        .arg(&out)
        .output()
        .expect("run matte");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).expect("json on stdout");
    let models = j["scenes"][0]["models"].as_array().expect("models");
    assert_eq!(models.len(), 5);
    assert_eq!(models[0]["model"], "lambert");
    assert_eq!(models[0]["ratio_global"].as_f64(), Some(1.0));
    let answers = j["answers"].as_array().expect("answers");
    assert!(answers.iter().any(|a| a.as_str().is_some_and(|t| t.contains("Wolff"))), "{answers:?}");
    for m in models {
        for k in ["ratio_global", "ratio_direct", "ratio_global_ci99", "ratio_direct_ci99"] {
            assert!(m[k].as_f64().is_some_and(f64::is_finite), "{k} of {}", m["model"]);
        }
    }
    let html = std::fs::read_to_string(out.join("report.html")).expect("report.html");
    let mut refs = 0;
    for part in html.split("src=\"").skip(1) {
        let file = part.split('"').next().unwrap();
        assert!(out.join(file).is_file(), "report names a missing file {file}");
        refs += 1;
    }
    assert_eq!(refs, 4, "two strips and two heatmap strips");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn region_mean_averages_the_covered_pixels() {
    use glam::Vec3;
    use matte::render::film::Image;
    // 4×2 image, pixel value = x + 10·y; region [0.5, 0, 1, 0.5] covers x = 2, 3 in row 0.
    let mut img = Image::new(4, 2);
    for y in 0..2 {
        for x in 0..4 {
            img.set(x, y, Vec3::splat((x + 10 * y) as f32));
        }
    }
    let m = matte::validate::passes::region_mean(&img, [0.5, 0.0, 1.0, 0.5]);
    assert!((m.x - 2.5).abs() < 1e-12, "{m}");
    let all = matte::validate::passes::region_mean(&img, [0.0, 0.0, 1.0, 1.0]);
    assert!((all.x - 6.5).abs() < 1e-12, "{all}");
}

#[test]
fn regions_file_is_read_and_validated() {
    let dir = std::env::temp_dir().join(format!("matte_regions_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("s.xml");
    assert!(matte::study::load_regions(&scene).unwrap().is_empty(), "no file, no regions");
    std::fs::write(dir.join("s.regions.json"), r#"{"regions":[{"name":"a","rect":[0.1,0.2,0.3,0.4]}]}"#).unwrap();
    let r = matte::study::load_regions(&scene).unwrap();
    assert_eq!(r.len(), 1);
    assert_eq!(r[0].rect, [0.1, 0.2, 0.3, 0.4]);
    std::fs::write(dir.join("s.regions.json"), r#"{"regions":[{"name":"a","rect":[0.5,0.2,0.3,0.4]}]}"#).unwrap();
    let e = matte::study::load_regions(&scene).unwrap_err();
    assert!(e.contains("s.regions.json") && e.contains("rect"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
