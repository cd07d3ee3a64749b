//! `matte study` plumbing: statistics helpers against closed forms, and a tiny end-to-end
//! run (its numbers are the study's business; here: Lambert's ratio to itself is exactly 1,
//! intervals are finite, and every file the report names exists).

use matte::study::metrics::{edge_vs_flat, mean_ci99};
use std::process::Command;

#[test]
fn mean_ci99_matches_the_t_quantile() {
    // Sample 1, 2, 3, 4: mean 2.5, s² = 5/3, se = sqrt(5/12); t(3) 0.995 quantile = 5.840909.
    let r = mean_ci99(&[1.0, 2.0, 3.0, 4.0]);
    let (m, hw) = (r.value, r.half_width);
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
    let scene = &crate::common::repo().join("mitsuba_scenes/sphere_lambert.xml").display().to_string();
    let o = Command::new(env!("CARGO_BIN_EXE_matte"))
        .envs(crate::common::source_package_env())
        .args(["study", scene, "--spp", "8", "--passes", "4", "--res", "24", "-q", "-o"])
        .arg(&out)
        .output()
        .expect("run matte");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j = study_json(&out);
    let models = j["scenes"][0]["models"].as_array().expect("models");
    // The paper's five, then every other registered model the study renders.
    let main_run = matte::study::configuration::main_run();
    assert_eq!(models.len(), main_run.len());
    assert!(main_run.len() >= 5);
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
    // The scene's $bsdf is in an included file: no true surfaces, and the report says why.
    assert!(j["scenes"][0]["notes"][0].as_str().is_some_and(|n| n.contains("$bsdf")), "{}", j["scenes"][0]["notes"]);
    assert!(j["truths"]["scenes"].as_array().is_some_and(Vec::is_empty));
    let _ = std::fs::remove_dir_all(&out);
}

/// study.json of a finished run in `out`.
fn study_json(out: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(out.join("study.json")).expect("study.json");
    serde_json::from_str(&text).expect("study.json is JSON")
}

/// `matte study` on the sphere scene at a tiny budget, main run only, with `extra` arguments:
/// its output folder and what it printed.
fn tiny_study(tag: &str, extra: &[&str]) -> (PathBuf, std::process::Output) {
    let out = temp_dir(tag);
    let scene = &crate::common::repo().join("mitsuba_scenes/sphere_lambert.xml").display().to_string();
    let o = Command::new(env!("CARGO_BIN_EXE_matte"))
        .envs(crate::common::source_package_env())
        .args(["study", scene, "--spp", "2", "--passes", "2", "--res", "8", "--no-variants", "--no-convergence"])
        .args(["--no-perceptual", "-q", "-o"])
        .arg(&out)
        .args(extra)
        .output()
        .expect("run matte");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (out, o)
}

#[test]
fn study_prints_the_answer_sentences_and_the_report_path_but_not_the_json() {
    let (out, o) = tiny_study("stdout_answers", &[]);
    let stdout = String::from_utf8(o.stdout).unwrap();
    assert!(serde_json::from_str::<serde_json::Value>(&stdout).is_err(), "{stdout}");
    assert!(!stdout.contains("\"scenes\""), "{stdout}");
    let lines: Vec<&str> = stdout.lines().collect();
    let answers = study_json(&out)["answers"].as_array().unwrap().clone();
    assert!(!answers.is_empty());
    assert_eq!(lines.len(), answers.len() + 1, "one line per answer, then the report's path: {stdout}");
    for (line, answer) in lines.iter().zip(&answers) {
        assert_eq!(Some(*line), answer.as_str());
    }
    let report = out.join("report.html").display().to_string();
    assert!(lines.last().unwrap().starts_with(&format!("report: {report}")), "{stdout}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn study_with_json_prints_study_json_and_nothing_else() {
    let (out, o) = tiny_study("stdout_json", &["--json"]);
    let printed: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
    assert_eq!(printed, study_json(&out));
    assert!(printed["scenes"][0]["models"].as_array().is_some_and(|m| !m.is_empty()));
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn report_opens_with_one_table_of_the_answers_per_scene_and_model() {
    let (out, _) = tiny_study("answer_table", &[]);
    let j = study_json(&out);
    let html = std::fs::read_to_string(out.join("report.html")).expect("report.html");
    let body = &html[html.find("<body>").unwrap()..];
    let table_at = body.find("<table").expect("a table");
    assert!(body[table_at..].starts_with("<table id=\"answers\">"), "the first table is the answers'");
    for later in ["<img", "<ul>", "<li>"] {
        assert!(body.find(later).is_none_or(|i| i > table_at), "{later} before the answer table");
    }
    let table = &body[table_at..table_at + body[table_at..].find("</table>").unwrap()];
    assert!(table.contains("<th>Δ</th>") && table.contains("difference under GI"));
    assert!(!table.contains("FLIP"), "no perceptual columns without the perceptual step");
    // One row per model against Lambert, in the main run's order, its ratios those of study.json.
    let models = j["scenes"][0]["models"].as_array().unwrap();
    let rows: Vec<Vec<&str>> = table
        .split("<tr>")
        .skip(2)
        .map(|row| row.split("<td").skip(1).map(|c| c.split('>').nth(1).unwrap().split('<').next().unwrap()).collect())
        .collect();
    let main_run = matte::study::configuration::main_run();
    assert_eq!(rows.len(), main_run.len() - 1);
    for (row, m) in rows.iter().zip(&main_run[1..]) {
        assert_eq!(row[0], "sphere_lambert");
        assert_eq!(row[1], m.label());
        let json = models.iter().find(|x| x["key"] == m.key()).unwrap();
        for (cell, key) in [(row[2], "ratio_global"), (row[3], "ratio_direct")] {
            let shown: f64 = cell.split(" ± ").next().unwrap().parse().unwrap();
            let decimals = cell.split(" ± ").next().unwrap().split('.').nth(1).map_or(0, str::len);
            let value = json[key].as_f64().unwrap();
            assert!((shown - value).abs() <= 0.5 * 10f64.powi(-(decimals as i32)) + 1e-12, "{cell} vs {value}");
        }
        assert!(row[4].ends_with('%'), "Δ in percent: {}", row[4]);
        assert!(["grows", "shrinks", "undecided", "direct only"].contains(&row[5]), "{}", row[5]);
    }
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn study_error_names_the_scene_and_the_section() {
    let out = temp_dir("error_names");
    let missing = out.join("missing.xml");
    let o = Command::new(env!("CARGO_BIN_EXE_matte"))
        .envs(crate::common::source_package_env())
        .args(["study", "--spp", "2", "--passes", "2", "--no-perceptual", "-q", "-o"])
        .arg(&out)
        .arg(&missing)
        .output()
        .expect("run matte");
    assert!(!o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains(&format!("{}: main run: ", missing.display())), "{stderr}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn region_mean_averages_the_covered_pixels() {
    use glam::Vec3;
    use matte_render::film::Image;
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

// ---- Derived scenes (model variants) -------------------------------------------------------

use matte::study::configuration::Configuration;
use matte::study::convergence::{Point, Series};
use matte::study::ratio::Ratio;
use matte::study::variant_scene::{Derivation, DerivedProperty, derive_text, write_derived};
use std::path::{Path, PathBuf};

fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("matte_study_{tag}_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

const SCENE: &str = r#"<?xml version="1.0"?>
<!-- a comment that stays -->
<scene version="3.0.0">
    <default name="bsdf" value="lambert"/>
    <include filename="parts/sub.xml"/>
    <bsdf type="$bsdf" id="a">
        <rgb name="reflectance" value="0.5"/>
    </bsdf>
    <bsdf type="diffuse" id="b"/>
    <bsdf type="twosided" id="c">
        <bsdf type="$bsdf"/>
    </bsdf>
    <bsdf type="$bsdf" id="d">
        <string name="normalization" value="physical"/>
    </bsdf>
    <shape type="obj">
        <string name="filename" value="meshes/a &amp; b.obj"/>
        <bsdf type="$bsdf"><rgb name="reflectance" value="0.3"/></bsdf>
    </shape>
    <shape type="ply"><string name="filename" value="/abs/mesh.ply"/><ref id="b"/></shape>
    <shape type="ply"><string name="filename" value="$mesh"/><ref id="b"/></shape>
    <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/></film></sensor>
</scene>
"#;

fn raw_variant() -> Derivation {
    Derivation {
        bsdf: Some("wolff".into()),
        bsdf_properties: vec![DerivedProperty::string("normalization", "raw")],
        ..Default::default()
    }
}

#[test]
fn derived_scene_sets_the_property_only_in_bsdf_parameter_elements() {
    let dir = temp_dir("derive");
    std::fs::create_dir_all(dir.join("parts")).unwrap();
    std::fs::write(dir.join("parts/sub.xml"), "<scene version=\"3.0.0\"><shape type=\"sphere\"/></scene>").unwrap();
    let source = dir.join("scene.xml");
    let mut d = raw_variant();
    d.film_properties = vec![DerivedProperty::integer("crop_offset_x", 3), DerivedProperty::integer("width", 16)];
    let out = derive_text(SCENE, &source, &d).expect("derive");
    let doc = roxmltree::Document::parse(&out).expect("the derived scene is well-formed XML");
    let mut param_bsdfs = 0;
    for b in doc.descendants().filter(|n| n.has_tag_name("bsdf")) {
        let props: Vec<_> = b.children().filter(|c| c.attribute("name") == Some("normalization")).collect();
        if b.attribute("type") == Some("$bsdf") {
            param_bsdfs += 1;
            assert_eq!(props.len(), 1, "exactly one normalization in bsdf {:?}", b.attribute("id"));
            assert_eq!(props[0].tag_name().name(), "string");
            assert_eq!(props[0].attribute("value"), Some("raw"));
        } else {
            assert!(props.is_empty(), "bsdf {:?} ({:?}) must stay untouched", b.attribute("id"), b.attribute("type"));
        }
    }
    assert_eq!(param_bsdfs, 4);
    let c = doc.descendants().find(|n| n.attribute("id") == Some("c")).unwrap();
    assert_eq!(c.children().filter(|n| n.is_element()).count(), 1, "twosided keeps only its nested bsdf");
    let a = doc.descendants().find(|n| n.attribute("id") == Some("a")).unwrap();
    assert!(a.children().any(|n| n.attribute("name") == Some("reflectance")), "existing children are kept");
    let default = doc.descendants().find(|n| n.has_tag_name("default")).unwrap();
    assert_eq!(default.attribute("value"), Some("wolff"));
    let film = doc.descendants().find(|n| n.has_tag_name("film")).unwrap();
    let fval =
        |name: &str| film.children().find(|c| c.attribute("name") == Some(name)).and_then(|c| c.attribute("value"));
    assert_eq!(fval("crop_offset_x"), Some("3"));
    assert_eq!(fval("width"), Some("16"), "an existing film property is replaced, not duplicated");
    assert_eq!(film.children().filter(|c| c.attribute("name") == Some("width")).count(), 1);
    assert!(out.contains("a comment that stays"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn derived_scene_makes_relative_file_names_absolute() {
    let dir = temp_dir("paths");
    std::fs::create_dir_all(dir.join("parts")).unwrap();
    std::fs::write(dir.join("parts/sub.xml"), "<scene version=\"3.0.0\"/>").unwrap();
    let source = dir.join("scene.xml");
    let out = derive_text(SCENE, &source, &raw_variant()).expect("derive");
    let doc = roxmltree::Document::parse(&out).unwrap();
    let include = doc.descendants().find(|n| n.has_tag_name("include")).unwrap();
    assert_eq!(include.attribute("filename").map(PathBuf::from), Some(dir.join("parts/sub.xml")));
    let names: Vec<&str> = doc
        .descendants()
        .filter(|n| n.attribute("name") == Some("filename"))
        .filter_map(|n| n.attribute("value"))
        .collect();
    assert_eq!(
        names[0],
        dir.join("meshes/a & b.obj").to_str().unwrap(),
        "relative name joined to the scene's folder (entities kept)"
    );
    assert_eq!(names[1], "/abs/mesh.ply", "absolute names are kept");
    assert_eq!(names[2], "$mesh", "parameters are left to their value");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn derived_scene_errors_name_the_file() {
    let dir = temp_dir("errors");
    let source = dir.join("broken.xml");
    let e = derive_text("<scene><bsdf type=\"$bsdf\"></scene>", &source, &raw_variant()).unwrap_err();
    assert!(e.contains("broken.xml") && e.contains("malformed"), "{e}");
    let e =
        derive_text("<scene version=\"3.0.0\"><bsdf type=\"diffuse\"/></scene>", &source, &raw_variant()).unwrap_err();
    assert!(e.contains("broken.xml") && e.contains("$bsdf"), "{e}");
    let clash =
        "<scene version=\"3.0.0\"><bsdf type=\"$bsdf\"><float name=\"normalization\" value=\"1\"/></bsdf></scene>";
    let e = derive_text(clash, &source, &raw_variant()).unwrap_err();
    assert!(e.contains("broken.xml") && e.contains("line 1") && e.contains("normalization"), "{e}");
    // An included file naming a relative asset would resolve against the derived scene's folder.
    std::fs::write(
        dir.join("sub.xml"),
        "<scene version=\"3.0.0\">\n<shape type=\"obj\"><string name=\"filename\" value=\"m.obj\"/></shape></scene>",
    )
    .unwrap();
    let inc = "<scene version=\"3.0.0\"><include filename=\"sub.xml\"/><bsdf type=\"$bsdf\"/></scene>";
    let e = derive_text(inc, &source, &raw_variant()).unwrap_err();
    assert!(e.contains("sub.xml") && e.contains("line 2") && e.contains("m.obj"), "{e}");
    let e = write_derived(&dir.join("missing.xml"), &dir.join("out.xml"), &raw_variant()).unwrap_err();
    assert!(e.contains("missing.xml"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `F_dr(η) = 2 ∫₀¹ F(μ, η) μ dμ` with the unpolarised Fresnel reflectance of
/// `docs/models.md#fresnel` (total internal reflection: F = 1), by a 10⁶-point midpoint rule.
fn diffuse_fresnel(eta: f64) -> f64 {
    let fresnel = |c: f64| {
        let g2 = eta * eta - 1.0 + c * c;
        if g2 < 0.0 {
            return 1.0;
        }
        let g = g2.sqrt();
        let a = (g - c) / (g + c);
        let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
        0.5 * a * a * (1.0 + b * b)
    };
    let n = 1_000_000;
    (0..n).map(|i| (i as f64 + 0.5) / n as f64).map(|mu| 2.0 * fresnel(mu) * mu / n as f64).sum()
}

#[test]
fn derived_wolff_raw_renders_brighter_than_physical_by_the_closed_form_factor() {
    use matte::validate::passes::{Budget, PassPlan, rust_side};
    use matte_render::film::SplatWeights;
    // Closed form (`docs/models.md#wolff-normalisations`): K_raw / K_physical = n² (1 − ρ F_dr,int), F_dr,int = F_dr(1/n).
    // With direct lighting only (max_depth 2) every path has one bounce, on the same geometry
    // with the same seed, so a region seeing only white surfaces scales by exactly that factor
    // per channel (> 1 for ρ below (1 − 1/n²) / F_dr,int ≈ 0.93: raw is brighter).
    let n = 1.4f64;
    let f_int = diffuse_fresnel(1.0 / n);
    let white = [0.885809f64, 0.698859, 0.666422];
    let dir = temp_dir("wolff");
    let cornell = crate::common::repo().join("mitsuba_scenes/study/cornell.xml");
    let back_wall = [0.35f64, 0.25, 0.65, 0.45];
    let render = |normalization: &str| {
        let file = dir.join(format!("{normalization}.xml"));
        let d = Derivation {
            bsdf: Some("wolff".into()),
            bsdf_properties: vec![DerivedProperty::string("normalization", normalization)],
            ..Default::default()
        };
        write_derived(&cornell, &file, &d).expect("derive");
        let defines = vec![
            ("bsdf".to_string(), "wolff".to_string()),
            ("max_depth".into(), "2".into()),
            ("res".into(), "32".into()),
        ];
        let plan = PassPlan { passes: 1, spp: Budget::PerPass(8), seed: 5, defines, regions: vec![back_wall] };
        rust_side(&file, &plan, SplatWeights::default(), &|_| {})
            .expect("the derived scene loads (absolute mesh paths) and renders")
            .region_pass_means[0][0]
    };
    let raw = render("raw");
    let physical = render("physical");
    for (c, (r, p)) in [(raw.x, physical.x), (raw.y, physical.y), (raw.z, physical.z)].into_iter().enumerate() {
        let expected = n * n * (1.0 - white[c] * f_int);
        assert!(expected > 1.0);
        assert!(
            p > 0.0 && (r / p / expected - 1.0).abs() < 1e-5,
            "channel {c}: raw/physical = {} (expected {expected})",
            r / p
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

// ---- Convergence series ----------------------------------------------------------------------

#[test]
fn crop_box_holds_exactly_the_region_pixels() {
    use glam::Vec3;
    use matte_render::film::Image;
    // Pixel value = its index: the mean over the crop box equals region_mean for odd sizes and
    // fractions that fall between pixels.
    for (w, h, r) in
        [(256u32, 256u32, [0.5f64, 0.9, 0.8, 0.97]), (17, 9, [0.1, 0.33, 0.71, 0.5]), (8, 8, [0.99, 0.99, 1.0, 1.0])]
    {
        let mut img = Image::new(w, h);
        for y in 0..h {
            for x in 0..w {
                img.set(x, y, Vec3::splat((y * w + x) as f32));
            }
        }
        let matte::validate::crop::PixelBox { x0, y0, x1, y1 } = matte::validate::crop::pixel_box(w, h, r);
        assert!(x0 < x1 && x1 <= w && y0 < y1 && y1 <= h);
        let mut sum = 0.0;
        for y in y0..y1 {
            for x in x0..x1 {
                sum += (y * w + x) as f64;
            }
        }
        let crop_mean = sum / ((x1 - x0) * (y1 - y0)) as f64;
        let region = matte::validate::passes::region_mean(&img, r).x;
        assert!((crop_mean - region).abs() < 1e-9 * region.max(1.0), "{w}x{h} {r:?}: {crop_mean} vs {region}");
    }
}

#[test]
fn convergence_verdicts_follow_interval_overlap() {
    let on = Configuration::OrenNayarQualitative;
    let pt = |spp, renderer: &str, (value, half_width)| Point {
        spp,
        renderer: renderer.into(),
        model: on,
        ratio: Ratio::new(value, half_width),
        seconds: 0.0,
    };
    let series = |points| Series {
        scene_name: "s".into(),
        region: "r".into(),
        crop: [0, 0, 1, 1],
        film: [1, 1],
        passes: 8,
        levels: vec![16, 64, 256],
        renderers: vec!["matte".into(), "mitsuba".into()],
        points,
        notes: Vec::new(),
    };
    // Intervals [0.80, 0.90], [0.84, 0.86], [0.845, 0.855]: all overlap the 256-spp one.
    let stable = series(vec![
        pt(16, "matte", (0.85, 0.05)),
        pt(64, "matte", (0.85, 0.01)),
        pt(256, "matte", (0.85, 0.005)),
        pt(16, "mitsuba", (0.86, 0.05)),
        pt(64, "mitsuba", (0.86, 0.02)),
        pt(256, "mitsuba", (0.851, 0.005)),
    ]);
    assert_eq!(stable.stable(on, "matte"), (3, 3));
    assert_eq!(stable.agreement(on), (3, 3));
    assert_eq!(stable.best(on, "mitsuba").map(|p| p.spp), Some(256));
    // Drift: 1.10 ± 0.01 at 16 spp misses 0.85 ± 0.005; renderers 0.85 vs 0.95 disagree at 256.
    let drift = series(vec![
        pt(16, "matte", (1.10, 0.01)),
        pt(64, "matte", (0.86, 0.01)),
        pt(256, "matte", (0.85, 0.005)),
        pt(256, "mitsuba", (0.95, 0.01)),
    ]);
    assert_eq!(drift.stable(on, "matte"), (2, 3));
    assert_eq!(drift.agreement(on), (0, 1));
    let answers = matte::study::answers::convergence_answers(&drift, None);
    assert!(answers.iter().any(|a| a.contains("drifts")), "{answers:?}");
    let answers = matte::study::answers::convergence_answers(&stable, None);
    assert!(answers.iter().any(|a| a.contains("not a bias") && a.contains("darker than Lambert")), "{answers:?}");
}

#[test]
fn study_with_variants_and_convergence_says_when_mitsuba_is_missing() {
    let out = temp_dir("e2e_variants");
    let scene = &crate::common::repo().join("mitsuba_scenes/study/cornell.xml").display().to_string();
    let o = Command::new(env!("CARGO_BIN_EXE_matte"))
        .envs(crate::common::source_package_env())
        .args(["study", scene, "--spp", "4", "--passes", "2", "--res", "16", "--convergence-spp", "2,4", "-q", "-o"])
        .arg(&out)
        .output()
        .expect("run matte");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j = study_json(&out);
    let v = &j["variants"][0];
    let rows = v["variants"].as_array().expect("variant rows");
    assert_eq!(rows.len(), 5);
    let main_wolff = j["scenes"][0]["models"].as_array().unwrap().iter().find(|m| m["model"] == "wolff").unwrap();
    let physical = rows.iter().find(|r| r["key"] == "wolff_physical").unwrap();
    assert_eq!(physical["ratio_global"], main_wolff["ratio_global"], "the default variant is the main run");
    for r in rows {
        assert!(
            r["ratio_global"].as_f64().is_some_and(f64::is_finite)
                && r["ratio_direct_ci99"].as_f64().is_some_and(f64::is_finite),
            "{r}"
        );
        if r["main_run"] == false {
            assert!(out.join(r["scene_file"].as_str().unwrap()).is_file());
        }
    }
    let c = &j["convergence"][0];
    assert_eq!(c["renderers"], serde_json::json!(["matte"]));
    assert_eq!(c["points"].as_array().unwrap().len(), 4, "2 levels × (ON, ON full), matte only");
    assert!(
        c["notes"][0].as_str().is_some_and(|n| n.contains("Mitsuba was not run") && n.contains("no Mitsuba")),
        "{}",
        c["notes"]
    );
    let html = std::fs::read_to_string(out.join("report.html")).expect("report.html");
    assert!(html.contains("Mitsuba was not run"));
    for part in html.split("src=\"").skip(1).chain(html.split("href=\"").skip(1)) {
        let file = part.split('"').next().unwrap();
        assert!(out.join(file).is_file(), "report names a missing file {file}");
    }
    let _ = std::fs::remove_dir_all(&out);
}

// ---- True surfaces ---------------------------------------------------------------------------

fn study_options(out: &Path) -> matte::study::StudyOptions {
    matte::study::StudyOptions {
        out: out.to_path_buf(),
        passes: 2,
        spp: 2,
        seed: 0,
        res: None,
        renderer: matte::validate::passes::Renderer::Matte,
        defines: Vec::new(),
        variant_scenes: Vec::new(),
        convergence_spp: Vec::new(),
        mitsuba_variant: "scalar_rgb".into(),
        ground_truth: crate::common::repo().join("python/matte_mitsuba/ground_truth"),
        truth_slices: None,
        perceptual: false,
    }
}

#[test]
fn every_true_surface_has_its_table_in_the_package() {
    let tables = crate::common::repo().join("python/matte_mitsuba/ground_truth");
    for t in matte::study::configuration::TRUTHS {
        let file = tables.join(t.table().expect("a true surface names its table"));
        assert!(file.is_file(), "{}", file.display());
    }
}

#[test]
fn derived_true_surface_scene_names_its_table_by_an_absolute_existing_path() {
    use matte::study::configuration::TRUTHS;
    let out = temp_dir("truth_scene");
    let cornell = crate::common::repo().join("mitsuba_scenes/study/cornell.xml");
    for t in TRUTHS {
        let file =
            matte::study::derived_scene(&cornell, t, &study_options(&out), Path::new("cornell/truth")).expect("derive");
        let text = std::fs::read_to_string(out.join(&file)).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let default = doc.descendants().find(|n| n.has_tag_name("default") && n.attribute("name") == Some("bsdf"));
        assert_eq!(default.and_then(|d| d.attribute("value")), Some("tabulated_brdf"));
        let mut n = 0;
        for b in doc.descendants().filter(|b| b.attribute("type") == Some("$bsdf")) {
            let f = b.children().find(|c| c.attribute("name") == Some("filename")).expect("a filename in every $bsdf");
            let path = PathBuf::from(f.attribute("value").unwrap());
            assert!(path.is_absolute() && path.is_file(), "{}", path.display());
            assert_eq!(path.file_name().and_then(|s| s.to_str()), t.table());
            n += 1;
        }
        assert_eq!(n, 3, "cornell's white, green and red");
    }
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn truth_ratio_and_growth_match_hand_computed_values() {
    use glam::DVec3;
    use matte::study::metrics::{growth, mean_ci99, pass_ratios};
    use matte::study::ratio::Verdict;
    // Per-pass model / surface: global 0.90, 0.92, 0.94, 0.96 (mean 0.93, s² = 0.002/3);
    // direct 0.95, 0.96, 0.97, 0.96 (mean 0.96). Luminance of a grey (x, x, x) is x.
    let truth: Vec<DVec3> = [2.0, 3.0, 4.0, 5.0].iter().map(|&x| DVec3::splat(x)).collect();
    let scaled = |r: [f64; 4]| -> Vec<DVec3> { truth.iter().zip(r).map(|(t, r)| *t * r).collect() };
    let g = pass_ratios(&scaled([0.90, 0.92, 0.94, 0.96]), &truth);
    let d = pass_ratios(&scaled([0.95, 0.96, 0.97, 0.96]), &truth);
    let t995 = 5.840909; // Student t, 3 degrees of freedom, 0.995
    let r = mean_ci99(&g);
    assert!((r.value - 0.93).abs() < 1e-12 && (r.half_width - t995 * (0.002f64 / 3.0 / 4.0).sqrt()).abs() < 1e-6);
    // Δ_k = −(g_k − 1) + (d_k − 1) = 0.05, 0.04, 0.03, 0.00: mean 0.03 = |0.93 − 1| − |0.96 − 1|,
    // s² = 0.0014/3.
    let delta = growth(&g, &d);
    assert!((delta.value - 0.03).abs() < 1e-12, "{delta:?}");
    assert!((delta.half_width - t995 * (0.0014f64 / 3.0 / 4.0).sqrt()).abs() < 1e-6, "{delta:?}");
    assert_eq!(Verdict::of(delta, false), Verdict::Undecided);
    // Above 1 under global illumination: its sign flips, Δ = (1.10 − 1) − |0.96 − 1| = 0.06.
    let g_up = pass_ratios(&scaled([1.09, 1.10, 1.11, 1.10]), &truth);
    let up = growth(&g_up, &d);
    assert!((up.value - 0.06).abs() < 1e-12, "{up:?}");
    assert_eq!(Verdict::of(up, false), Verdict::Grows);
    assert_eq!(Verdict::of(growth(&d, &g_up), false), Verdict::Shrinks);
    assert_eq!(Verdict::of(up, true), Verdict::DirectOnly);
}

#[test]
fn study_compares_each_rough_model_with_its_own_surface() {
    let out = temp_dir("e2e_truth");
    let scene = &crate::common::repo().join("mitsuba_scenes/study/cornell.xml").display().to_string();
    let o = Command::new(env!("CARGO_BIN_EXE_matte"))
        .envs(crate::common::source_package_env())
        .args(["study", scene, "--spp", "4", "--passes", "2", "--res", "16", "--no-variants", "--no-convergence"])
        .args(["-q", "-o"])
        .arg(&out)
        .output()
        .expect("run matte");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j = study_json(&out);
    let models = j["scenes"][0]["models"].as_array().expect("models");
    let by_key = |k: &str| models.iter().find(|m| m["key"] == k).unwrap_or_else(|| panic!("no {k} in {models:?}"));
    for k in ["truth_v_cavities", "truth_height_field"] {
        assert!(by_key(k)["ratio_global"].as_f64().is_some_and(f64::is_finite), "{k}: its ratio to Lambert");
    }
    let truth = &j["truths"]["scenes"][0];
    let comparisons = truth["comparisons"].as_array().expect("comparisons");
    let keys: Vec<&str> = comparisons.iter().map(|c| c["model"].as_str().unwrap()).collect();
    assert_eq!(keys, ["oren_nayar_qualitative", "oren_nayar_full", "eon", "ginneken"]);
    assert_eq!(j["truths"]["without_surface"][0], "lambert");
    for c in comparisons {
        for k in ["ratio_global", "ratio_global_ci99", "ratio_direct", "growth", "growth_ci99"] {
            assert!(c[k].as_f64().is_some_and(f64::is_finite), "{k} of {c}");
        }
        assert!(["grows", "shrinks", "undecided"].contains(&c["verdict"].as_str().unwrap()), "{c}");
        if c["model"] == "oren_nayar_full" {
            continue; // rendered for the comparison only, not in the main run
        }
        // Per pass, model / surface = (model / Lambert) / (surface / Lambert) up to rounding.
        let (m, t) = (by_key(c["model"].as_str().unwrap()), by_key(c["truth"].as_str().unwrap()));
        for l in ["global", "direct"] {
            let key = format!("pass_ratios_{l}");
            let (direct, ml, tl) =
                (c[&key].as_array().unwrap(), m[&key].as_array().unwrap(), t[&key].as_array().unwrap());
            assert_eq!(direct.len(), 2);
            for ((r, a), b) in direct.iter().zip(ml).zip(tl) {
                let (r, via) = (r.as_f64().unwrap(), a.as_f64().unwrap() / b.as_f64().unwrap());
                assert!((r / via - 1.0).abs() < 1e-12, "{} {l}: {r} vs {via}", c["model"]);
            }
        }
    }
    let full = truth["scene_file"].as_str().expect("Oren–Nayar full's derived scene");
    assert!(out.join(full).is_file());
    assert!(
        j["answers"].as_array().unwrap().iter().any(|a| a.as_str().unwrap().contains("closest to its own surface"))
    );
    let html = std::fs::read_to_string(out.join("report.html")).expect("report.html");
    assert!(html.contains("model / surface, global") && html.contains("describe no simulated surface"));
    let mut truth_strips = 0;
    for part in html.split("src=\"").skip(1) {
        let file = part.split('"').next().unwrap();
        assert!(out.join(file).is_file(), "report names a missing file {file}");
        truth_strips += file.starts_with("cornell/truth/difference_") as usize;
    }
    assert_eq!(truth_strips, 2, "a (model − surface) heatmap strip per lighting");
    assert!(out.join("truth.json").is_file());
    let _ = std::fs::remove_dir_all(&out);
}

// ---- Perceptual difference ---------------------------------------------------------------------

#[test]
fn jackknife_interval_is_the_t_quantile_times_the_jackknife_standard_error() {
    use matte::study::perceptual::jackknife_ci99;
    // K = 4 leave-one-out values: mean 0.25, Σ (θᵢ − θ̄)² = 0.05, se = √(3/4 · 0.05); t(3) at
    // 0.995 = 5.840909 (tables).
    let r = jackknife_ci99(0.3, &[0.1, 0.2, 0.3, 0.4]);
    let se = (0.75f64 * 0.05).sqrt();
    assert_eq!(r.value, 0.3, "the estimate is the full-budget value, not the replicates' mean");
    assert!((r.half_width - 5.840909 * se).abs() < 1e-5, "{}", r.half_width);
    assert_eq!(jackknife_ci99(0.2, &[0.2; 5]).half_width, 0.0);
    assert!(jackknife_ci99(0.2, &[0.2]).half_width.is_infinite(), "one pass: no interval");
}

#[test]
fn perceptual_and_energy_verdicts_agree_only_in_the_same_direction() {
    use matte::study::perceptual::{Agreement, Visibility};
    use matte::study::ratio::Verdict;
    let cases = [
        (Verdict::Grows, Visibility::MoreVisible, Agreement::Agree),
        (Verdict::Shrinks, Visibility::LessVisible, Agreement::Agree),
        (Verdict::Grows, Visibility::LessVisible, Agreement::Disagree),
        (Verdict::Shrinks, Visibility::MoreVisible, Agreement::Disagree),
        (Verdict::Grows, Visibility::WithinNoise, Agreement::EnergyOnly),
        (Verdict::Shrinks, Visibility::Undecided, Agreement::EnergyOnly),
        (Verdict::Undecided, Visibility::MoreVisible, Agreement::PerceptualOnly),
        (Verdict::Undecided, Visibility::WithinNoise, Agreement::Neither),
        (Verdict::DirectOnly, Visibility::DirectOnly, Agreement::Neither),
    ];
    for (e, p, want) in cases {
        assert_eq!(Agreement::of(e, p), want, "{e:?} {p:?}");
    }
}

#[test]
fn flip_map_tiles_use_flips_magma_scale_clamped_to_zero_one() {
    use matte::study::perceptual::{colour_bar, map_tile};
    let t = map_tile("x", 4, 1, &[0.0, 1.0, -3.0, f32::NAN]);
    // Magma's ends: black-violet at 0 (#000004), pale yellow at 1 (#fcfdbf).
    assert_eq!(&t.rgb[0..3], &[0, 0, 4]);
    assert_eq!(&t.rgb[3..6], &[252, 253, 191]);
    assert_eq!(&t.rgb[6..9], &[0, 0, 4], "below 0 is 0");
    assert!(t.rgb.len() == 12);
    let bar = colour_bar(64);
    assert_eq!(bar.height, 64);
    assert_eq!(&bar.rgb[0..3], &[252, 253, 191], "1 at the top");
}

#[test]
fn study_without_flip_evaluator_says_why_and_keeps_the_rest() {
    // The machine's python3 (the checkout's source package) has no flip-evaluator (nor
    // Mitsuba): the study runs, and the perceptual part is a note; --no-perceptual skips it.
    let scene = &crate::common::repo().join("mitsuba_scenes/study/cornell.xml").display().to_string();
    for skip in [false, true] {
        let out = temp_dir(if skip { "e2e_no_perceptual" } else { "e2e_perceptual_note" });
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_matte"));
        cmd.envs(crate::common::source_package_env())
            .args(["study", scene, "--spp", "2", "--passes", "2", "--res", "8", "--no-variants", "--no-convergence"])
            .args(["-q", "-o"])
            .arg(&out);
        if skip {
            cmd.arg("--no-perceptual");
        }
        let o = cmd.output().expect("run matte");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let j = study_json(&out);
        let p = &j["perceptual"];
        assert!(p["scenes"].as_array().is_some_and(Vec::is_empty), "{p}");
        let notes = p["notes"].as_array().unwrap();
        if skip {
            assert!(notes.is_empty(), "{notes:?}");
        } else {
            assert!(notes[0].as_str().is_some_and(|n| n.contains("not computed")), "{notes:?}");
            let html = std::fs::read_to_string(out.join("report.html")).expect("report.html");
            assert!(html.contains("perceptual differences were not computed"));
        }
        assert!(!out.join("cornell/perceptual_work").exists(), "the pass images are removed");
        let _ = std::fs::remove_dir_all(&out);
    }
}

// ---- Figures: the strips' labels and the convergence plot ---------------------------------

/// The label rows of a strip written by `write_strip`: (width, height, RGB8 pixels).
fn strip_pixels(tiles: &[matte::study::strip::StripTile], tag: &str) -> image::RgbImage {
    let path = temp_dir(tag).join("strip.png");
    matte::study::strip::write_strip(&path, tiles).unwrap();
    image::open(&path).unwrap().to_rgb8()
}

fn grey_tile(label: &str, width: u32) -> matte::study::strip::StripTile {
    matte::study::strip::StripTile { label: label.into(), width, height: 8, rgb: vec![128; (width * 8 * 3) as usize] }
}

#[test]
fn strip_labels_are_antialiased_one_size_and_inside_their_tiles() {
    use matte::study::font;
    use matte::study::strip::{LABEL_PX, MIN_LABEL_PX};
    // Three labels that fit 160-pixel tiles at the full size, then the same with one label too
    // long for its tile: every label shrinks with it, none leaves its tile's columns.
    for (long, tag) in [("EON", "strip_fit"), ("Oren–Nayar (qualitative), σ = 0.3", "strip_shrink")] {
        let tiles = [grey_tile("Lambert", 160), grey_tile("Wolff", 160), grey_tile(long, 160)];
        let img = strip_pixels(&tiles, tag);
        let label_rows = img.height() - 8;
        let ink: Vec<(u32, u32, u8)> = (0..label_rows)
            .flat_map(|y| (0..img.width()).map(move |x| (x, y)))
            .map(|(x, y)| (x, y, img.get_pixel(x, y)[0]))
            .filter(|p| p.2 < 250)
            .collect();
        // Tiles start at 4, 168, 332 (4-pixel gaps): ink only over a tile.
        assert!(ink.iter().all(|&(x, _, _)| x >= 4 && (x - 4) % 164 < 160), "{tag}: ink in a gap");
        for t in 0..3 {
            assert!(ink.iter().any(|&(x, _, _)| (x - 4) / 164 == t), "{tag}: tile {t} has no label");
        }
        assert!(ink.iter().any(|p| p.2 > 60 && p.2 < 200), "{tag}: no anti-aliased edge");
        // One size: the rows' height follows the one size chosen for the strip.
        let px = if tag == "strip_fit" { LABEL_PX } else { LABEL_PX * 158.0 / font::width(long, LABEL_PX) };
        assert!((MIN_LABEL_PX..=LABEL_PX).contains(&px), "{px}");
        let (a, d) = font::extent(px);
        assert_eq!(label_rows, (a - d).ceil() as u32 + 8, "{tag}");
        // "Lambert" is drawn at that size in both strips (its ink about its advance width).
        let lambert = ink.iter().filter(|p| p.0 < 164).map(|p| p.0);
        let span = lambert.clone().max().unwrap() - lambert.min().unwrap();
        assert!((span as f32 - font::width("Lambert", px)).abs() < 3.0, "{tag}: {span} at {px} px");
        assert!(tag == "strip_fit" || px < 0.9 * LABEL_PX, "{px}");
    }
}

#[test]
fn labels_too_long_at_the_smallest_size_are_shortened_to_fit() {
    use matte::study::font::{ellipsize, width};
    assert_eq!(ellipsize("Lambert", 16.0, 100.0), "Lambert");
    let short = ellipsize("Oren–Nayar (qualitative)", 9.0, 30.0);
    assert!(short.ends_with('…') && short.len() < "Oren–Nayar (qualitative)".len(), "{short}");
    assert!(width(&short, 9.0) <= 30.0);
    // A strip of narrow tiles: the labels are drawn at the smallest size, shortened, and
    // still leave the 4-pixel gaps between tiles blank.
    let img = strip_pixels(&[grey_tile("Oren–Nayar full", 24), grey_tile("van Ginneken", 24)], "strip_narrow");
    for y in 0..img.height() - 8 {
        for x in [0, 1, 2, 3, 28, 29, 30, 31] {
            assert_eq!(img.get_pixel(x, y).0, [255, 255, 255], "ink at ({x}, {y})");
        }
    }
}

fn series(ratios: &[(u32, &str, f64)]) -> matte::study::convergence::Series {
    use matte::study::configuration::Configuration;
    use matte::study::convergence::{Point, Series};
    use matte::study::ratio::Ratio;
    Series {
        scene_name: "cornell".into(),
        region: "floor".into(),
        crop: [0, 0, 4, 4],
        film: [8, 8],
        passes: 4,
        levels: vec![16, 64, 256],
        renderers: vec!["matte".into(), "mitsuba <scalar_rgb>".into()],
        points: ratios
            .iter()
            .map(|&(spp, renderer, value)| Point {
                spp,
                renderer: renderer.into(),
                model: Configuration::OrenNayarFull,
                ratio: Ratio::new(value, 0.01),
                seconds: 1.0,
            })
            .collect(),
        notes: Vec::new(),
    }
}

#[test]
fn convergence_plot_has_axes_ticks_legend_and_lamberts_level() {
    use matte::study::configuration::Configuration;
    use matte::study::report::plot::ratio_over_spp;
    let m = "mitsuba <scalar_rgb>";
    let around_one =
        series(&[(16, "matte", 0.99), (64, "matte", 1.0), (256, "matte", 1.01), (16, m, 1.0), (256, m, 1.0)]);
    let svg = ratio_over_spp(&around_one, Configuration::OrenNayarFull, "Oren–Nayar (full) / Lambert");
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"), "{svg}");
    for text in ["Oren–Nayar (full) / Lambert", "total spp", "region ratio to Lambert", "matte", "Lambert (1)"] {
        assert!(svg.contains(&format!(">\n{text}\n<")), "no text {text:?}");
    }
    // The levels are the x ticks; the renderer's name is escaped.
    for spp in ["16", "64", "256"] {
        assert!(svg.contains(&format!(">\n{spp}\n<")), "no tick {spp}");
    }
    assert!(svg.contains("mitsuba &lt;scalar_rgb&gt;") && !svg.contains("<scalar_rgb>"));
    assert!(svg.contains("font-family=\"DejaVu Sans, sans-serif\""));
    // Five points with error bars (a circle each) and the two legend markers.
    assert_eq!(svg.matches("<circle").count(), 5 + 2);
    // All the data far below 1: the legend says Lambert's level is above the plot.
    let below = series(&[(16, "matte", 0.8), (64, "matte", 0.81)]);
    let svg = ratio_over_spp(&below, Configuration::OrenNayarFull, "t");
    assert!(svg.contains("Lambert (1): ↑ above"), "{svg}");
    assert!(ratio_over_spp(&below, Configuration::OrenNayarQualitative, "t").is_empty(), "no points, no plot");
}
