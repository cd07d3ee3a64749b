//! `matte render` as a user runs it: the bundled feature scene renders, `-D` overrides scene
//! parameters, errors are one line with file and line, and `MATTE_ACCEL` chooses the ray-query
//! arrangement (a bad value is a one-line note). The loader and renderer themselves are the
//! renderer crate's tests (`tests/render/`).

use crate::common::{SENSOR, scene};
use glam::Vec3;
use std::path::PathBuf;
use std::process::Command;

/// [`SENSOR`] on line 2, `body` from line 3 on.
fn with_sensor(body: &str) -> String {
    scene(&format!("{SENSOR}\n{body}"))
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("matte_render_cli_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn matte(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_matte")).args(args).output().expect("run matte");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn features_xml() -> PathBuf {
    crate::common::repo().join("mitsuba_scenes/features.xml")
}

#[test]
fn cli_renders_features_xml() {
    let dir = temp_dir("cli_features");
    let exr = dir.join("features.exr");
    let scene = features_xml();
    let (ok, out, err) =
        matte(&["render", scene.to_str().unwrap(), "--spp", "2", "-o", exr.to_str().unwrap(), "--quiet", "--png"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap_or_else(|e| panic!("not JSON ({e}): {out}"));
    // The scene's crop window is 144×112 of a 160×120 film.
    let img = matte_render::image_io::read_exr(&exr).unwrap();
    assert_eq!((img.width, img.height), (144, 112));
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64(), v["spp"].as_u64(), v["seed"].as_u64()),
        (Some(144), Some(112), Some(2), Some(3))
    );
    assert_eq!(v["samples"].as_u64(), Some(144 * 112 * 2));
    assert!(v["rays"].as_u64().unwrap() >= 144 * 112 * 2, "{out}");
    assert!(v["samples_per_second"].as_f64().unwrap() > 0.0);
    assert!(img.pixels.iter().all(|p| p.is_finite() && p.min_element() >= 0.0));
    // Lit: the constant environment alone is (0.05, 0.06, 0.08) and there are brighter lights.
    let mean = img.pixels.iter().copied().sum::<Vec3>() / img.pixels.len() as f32;
    assert!(mean.min_element() > 0.01, "{mean}");
    assert!(dir.join("features.png").exists());
}

#[test]
fn cli_defines_override_scene_parameters() {
    let dir = temp_dir("cli_defines");
    // -D spp=1 on features.xml replaces its <default name="spp" value="64">.
    let exr = dir.join("f.exr");
    let (ok, out, err) =
        matte(&["render", features_xml().to_str().unwrap(), "-D", "spp=1", "-o", exr.to_str().unwrap(), "-q"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["spp"].as_u64(), Some(1));
    assert_eq!(v["samples"].as_u64(), Some(144 * 112));
    // -D res=32 changes the film width of a scene that uses $res.
    let scene = dir.join("small.xml");
    std::fs::write(
        &scene,
        "<scene version=\"3.0.0\">\n<default name=\"res\" value=\"8\"/>\n<sensor type=\"perspective\"><film type=\"hdrfilm\">\
         <integer name=\"width\" value=\"$res\"/><integer name=\"height\" value=\"4\"/></film></sensor>\n\
         <shape type=\"sphere\"/><emitter type=\"constant\"/>\n</scene>",
    )
    .unwrap();
    let exr = dir.join("small.exr");
    for (def, width) in [(None, 8), (Some("res=32"), 32)] {
        let mut args = vec!["render", scene.to_str().unwrap(), "--spp", "1", "-o", exr.to_str().unwrap(), "--quiet"];
        if let Some(d) = def {
            args.extend(["-D", d]);
        }
        let (ok, out, err) = matte(&args);
        assert!(ok, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["width"].as_u64(), Some(width));
        assert_eq!(matte_render::image_io::read_exr(&exr).unwrap().width, width as u32);
    }
}

#[test]
fn cli_errors_are_one_line_with_file_and_line() {
    let dir = temp_dir("cli_errors");
    let scene = dir.join("bad.xml");
    std::fs::write(&scene, with_sensor("<shape type=\"sphere\">\n<bsdf type=\"diffuse\">\n<float name=\"roughness\" value=\"0.1\"/>\n</bsdf>\n</shape>")).unwrap();
    let out = dir.join("bad.exr");
    let (ok, stdout, err) = matte(&["render", scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "--quiet"]);
    assert!(!ok);
    assert!(stdout.is_empty(), "{stdout}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains(&format!("{}:5", scene.display())) && err.contains("roughness"), "{err}");
    assert!(!out.exists());
    // An unknown -D parameter.
    let (ok, _, err) =
        matte(&["render", features_xml().to_str().unwrap(), "-D", "nope=1", "-o", out.to_str().unwrap(), "-q"]);
    assert!(!ok);
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("features.xml") && err.contains("nope=1"), "{err}");
    // A malformed -D and a missing scene file.
    let (ok, _, err) = matte(&["render", features_xml().to_str().unwrap(), "-D", "novalue", "-q"]);
    assert!(!ok && err.contains("NAME=VALUE"), "{err}");
    let (ok, _, err) = matte(&["render", dir.join("absent.xml").to_str().unwrap(), "-q"]);
    assert!(!ok && err.contains("absent.xml"), "{err}");
}

/// A bad `MATTE_ACCEL` is a one-line note, then the default; `cwbvh` renders the same image
/// statistics (here: the same finite, non-empty render).
#[test]
fn matte_accel_chooses_the_backend_and_a_bad_value_is_a_note() {
    let root = crate::common::repo();
    let out = std::env::temp_dir().join("matte_accel_backend_test.exr");
    let render = |accel: &str| {
        Command::new(env!("CARGO_BIN_EXE_matte"))
            .current_dir(&root)
            .env("MATTE_ACCEL", accel)
            .args(["render", "mitsuba_scenes/cornell_box.xml", "-D", "res=16", "--spp", "2", "-q", "-o"])
            .arg(&out)
            .output()
            .unwrap()
    };
    for accel in ["embree", "embree-meshes", "cwbvh"] {
        let o = render(accel);
        assert!(o.status.success(), "{accel}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(o.stderr.is_empty(), "{accel}: {}", String::from_utf8_lossy(&o.stderr));
    }
    let o = render("optix");
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("matte: note: MATTE_ACCEL=\"optix\""), "{err}");
}
