//! `matte brdf` / `matte albedo` as a user runs them: JSON for every plugin type, values
//! equal to the kernels', and one-line errors with a non-zero exit code for bad input.

use crate::common;
use matte_brdf::frame::spherical_direction;
use matte_brdf::{BSDF_TYPES, DiffuseBrdf};
use std::process::Command;

fn matte(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_matte")).args(args).output().expect("run matte");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn brdf_answers_for_every_type() {
    // A type with a file parameter (tabulated_brdf) reads the packaged V-cavity table.
    let table = common::repo().join("python/matte_mitsuba/ground_truth/v_cavities_sigma0.3.json").display().to_string();
    for kind in BSDF_TYPES {
        let file = !matte_brdf::spec(kind).unwrap().builds_from_defaults();
        let params: Vec<(&str, &str)> = if file { vec![("filename", table.as_str())] } else { vec![] };
        let mut args: Vec<String> =
            ["brdf", "--bsdf", kind, "--reflectance", "0.8", "--theta-i", "30", "--theta-o", "60", "--phi", "45"]
                .map(String::from)
                .to_vec();
        for (k, v) in &params {
            args.extend(["--param".to_string(), format!("{k}={v}")]);
        }
        let (ok, out, err) = matte(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(ok, "{kind}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let bsdf = common::model(kind, &params);
        let (wi, wo) =
            (spherical_direction(30f32.to_radians(), 0.0), spherical_direction(60f32.to_radians(), 45f32.to_radians()));
        let want = bsdf.eval(wi, wo, [0.8])[0];
        let got = v["f"].as_f64().unwrap() as f32;
        assert!((got - want).abs() <= 1e-6 * want, "{kind}: {got} vs {want}");
        let pdf = v["pdf"].as_f64().unwrap();
        assert!((pdf - bsdf.pdf(wi, wo) as f64).abs() < 1e-6, "{kind}: pdf {pdf}");
        if !bsdf.own_sampler() {
            // The cosine: cos 60° / π.
            assert!((pdf - 0.5 / std::f64::consts::PI).abs() < 1e-6, "{kind}: pdf {pdf}");
        }
        assert_eq!(v["bsdf"], *kind);
    }
}

#[test]
fn parameters_and_grid() {
    let (ok, out, err) = matte(&[
        "brdf",
        "--bsdf",
        "oren_nayar",
        "--param",
        "sigma=0.5",
        "--param",
        "model=full",
        "--reflectance",
        "0.8",
        "--grid",
        "4",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["params"]["model"], "full");
    assert_eq!(v["f"].as_array().unwrap().len(), 4);
    assert_eq!(v["f"][0][0].as_array().unwrap().len(), 4);
    // θi = θo = 0: fullON s=0.5 at ρ = 0.8 is 0.22255 (`docs/models.md` Table 1).
    assert!((v["f"][0][0][0].as_f64().unwrap() - 0.22255).abs() < 2e-5);
}

#[test]
fn albedo_reports_method() {
    let (ok, out, err) = matte(&["albedo", "--bsdf", "wolff", "--param", "int_ior=1.5", "--theta-i", "60"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!((v["albedo"].as_f64().unwrap() - 0.9108).abs() < 1e-4);
    assert_eq!(v["method"], "closed form");
}

#[test]
fn a_malformed_scene_is_reported_on_one_line() {
    // The XML parser quotes the character it did not expect, here a line break.
    let dir = std::env::temp_dir().join(format!("matte-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("broken.xml");
    std::fs::write(&file, "<scene version=\"3.0.0\">\n  <bsdf type=\"diffuse\" id=\"a\"/\n>\n</scene>\n").unwrap();
    let out_file = dir.join("out.exr");
    let (ok, out, err) = matte(&["render", file.to_str().unwrap(), "-o", out_file.to_str().unwrap()]);
    assert!(!ok, "a malformed scene rendered: {out}");
    assert_eq!(err.trim_end().lines().count(), 1, "not one line:\n{err}");
    assert!(err.contains("broken.xml:2:"), "no file:line in {err}");
    assert!(err.contains("\\n"), "the line break is not shown escaped: {err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn invalid_input_is_one_line_and_non_zero() {
    for args in [
        vec!["brdf", "--bsdf", "phong", "--theta-i", "0", "--theta-o", "0", "--phi", "0"],
        vec!["brdf", "--bsdf", "oren_nayar", "--param", "sigma=-1", "--theta-i", "0", "--theta-o", "0", "--phi", "0"],
        vec!["brdf", "--bsdf", "wolff", "--param", "int_ior=0.5", "--theta-i", "0", "--theta-o", "0", "--phi", "0"],
        vec!["brdf", "--bsdf", "eon", "--param", "roughness", "--theta-i", "0", "--theta-o", "0", "--phi", "0"],
        vec!["brdf", "--bsdf", "lambert", "--reflectance", "1.5", "--theta-i", "0", "--theta-o", "0", "--phi", "0"],
        vec!["brdf", "--bsdf", "lambert", "--theta-i", "abc", "--theta-o", "0", "--phi", "0"],
        vec!["brdf", "--bsdf", "lambert", "--theta-i", "0"],
        vec!["albedo", "--bsdf", "ginneken", "--param", "roughness=0", "--theta-i", "0"],
    ] {
        let (ok, out, err) = matte(&args);
        assert!(!ok, "{args:?} succeeded: {out}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: not one line:\n{err}");
        assert!(out.is_empty(), "{args:?}: printed to stdout: {out}");
    }
}

#[test]
fn the_readme_model_table_is_the_registry() {
    let readme = std::fs::read_to_string(common::repo().join("README.md")).unwrap();
    let table = matte::cli::types_cmd::markdown_table();
    assert!(readme.contains(&table), "README.md's model table differs from `matte types --markdown`:\n{table}");
}
