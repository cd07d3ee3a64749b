//! The samplers (`matte_render::sampler`) and the `thinlens` sensor against live Mitsuba
//! 3.9.1: `tests/render/samplers/mitsuba_reference.json` was written by
//! `tests/render/samplers/generate_reference.py` (scalar_rgb) and holds each sampler's rounded
//! `sample_count`, the numbers it draws after `sampler.seed(s)` and `thinlens` rays. A second
//! check is a closed form: every sampler's per-pixel streams integrate a smooth function of
//! several dimensions to its known value.

use glam::{Vec2, Vec3};
use matte_render::load::load_str;
use matte_render::sampler::{Sampler, SamplerKind, Sampling};
use matte_render::sensor::Camera;
use serde_json::Value;
use std::path::Path;

fn reference() -> Value {
    let path = crate::common::repo().join("tests/render/samplers/mitsuba_reference.json");
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn kind(case: &Value) -> SamplerKind {
    let props = &case["props"];
    let jitter = props.get("jitter").map(|j| j.as_bool().unwrap()).unwrap_or(true);
    let strength = props.get("strength").map(|s| s.as_u64().unwrap() as u32).unwrap_or(2);
    match case["type"].as_str().unwrap() {
        "stratified" => SamplerKind::Stratified { jitter },
        "multijitter" => SamplerKind::Multijitter { jitter },
        "orthogonal" => SamplerKind::Orthogonal { jitter, strength },
        "ldsampler" => SamplerKind::LowDiscrepancy,
        "independent" => SamplerKind::Independent,
        other => panic!("unknown sampler {other}"),
    }
}

#[test]
fn sample_counts_are_rounded_as_mitsuba_rounds_them() {
    for case in reference()["rounding"].as_array().unwrap() {
        let n = case["n"].as_u64().unwrap() as u32;
        let k = kind(&serde_json::json!({"type": case["type"], "props": {}}));
        assert_eq!(k.round_sample_count(n) as u64, case["count"].as_u64().unwrap(), "{} with {n}", case["type"]);
    }
}

/// Given Mitsuba's seeding (`Sampler::mitsuba`), every sampler draws Mitsuba's numbers: the
/// same dimensions of the same samples, to f32 rounding of the jitter arithmetic.
#[test]
fn every_sampler_draws_mitsubas_sequence() {
    for case in reference()["samplers"].as_array().unwrap() {
        let k = kind(case);
        let n = case["n"].as_u64().unwrap() as u32;
        assert_eq!(k.round_sample_count(n) as u64, case["count"].as_u64().unwrap());
        let mut s =
            Sampler::mitsuba(k, n, case["base"].as_u64().unwrap() as u32, case["seed"].as_u64().unwrap() as u32);
        let rows = case["vals"].as_array().unwrap();
        assert_eq!(rows.len() as u64, case["count"].as_u64().unwrap());
        for (i, row) in rows.iter().enumerate() {
            let mut mine = Vec::new();
            for d in 0..6 {
                if d % 2 == 0 {
                    mine.push(s.next_1d());
                } else {
                    let p = s.next_2d();
                    mine.extend([p.x, p.y]);
                }
            }
            s.advance();
            for (j, (m, want)) in mine.iter().zip(row.as_array().unwrap()).enumerate() {
                let want = want.as_f64().unwrap() as f32;
                assert!(
                    (m - want).abs() <= 2e-6,
                    "{} {:?}: sample {i} value {j}: {m} vs Mitsuba {want}",
                    case["type"],
                    case["props"]
                );
            }
        }
    }
}

/// ∫ over [0,1)^5 of (1 + cos 2πx)·(2y)·(3z²)·(u + v) = 1 · 1 · 1 · 1 = 1: the mean over many
/// pixels' streams, each sampler at its rounded count, is 1 within a few standard errors
/// (the independent sampler's spread bounds the others').
#[test]
fn every_sampler_integrates_to_the_closed_form() {
    let kinds = [
        SamplerKind::Independent,
        SamplerKind::Stratified { jitter: true },
        SamplerKind::Multijitter { jitter: true },
        SamplerKind::Orthogonal { jitter: true, strength: 2 },
        SamplerKind::Orthogonal { jitter: true, strength: 3 },
        SamplerKind::LowDiscrepancy,
    ];
    for k in kinds {
        let sampling = Sampling::new(k, 16, 3);
        let pixels = 4000u64;
        let (mut sum, mut sum2) = (0f64, 0f64);
        for p in 0..pixels {
            let mut s = sampling.sampler(p);
            let mut acc = 0f64;
            for _ in 0..sampling.spp {
                let x = s.next_1d() as f64;
                let yz = s.next_2d();
                let uv = s.next_2d();
                let f = (1.0 + (2.0 * std::f64::consts::PI * x).cos())
                    * (2.0 * yz.x as f64)
                    * (3.0 * (yz.y as f64).powi(2))
                    * (uv.x + uv.y) as f64;
                acc += f;
                s.advance();
            }
            let m = acc / sampling.spp as f64;
            sum += m;
            sum2 += m * m;
        }
        let mean = sum / pixels as f64;
        let se = ((sum2 / pixels as f64 - mean * mean) / pixels as f64).sqrt();
        assert!((mean - 1.0).abs() < 4.0 * se + 1e-3, "{}: mean {mean} ± {se}", k.name());
    }
}

/// `thinlens` rays (origin on the near plane, direction, extent) for film and aperture samples,
/// the sensor read from XML as a scene gives it.
#[test]
fn thinlens_rays_match_mitsuba() {
    let r = &reference()["thinlens"];
    let p = &r["props"];
    let v = |a: &Value| format!("{}, {}, {}", a[0], a[1], a[2]);
    let xml = format!(
        r#"<scene version="3.0.0">
<sensor type="thinlens">
<float name="fov" value="{}"/><string name="fov_axis" value="{}"/>
<float name="aperture_radius" value="{}"/><float name="focus_distance" value="{}"/>
<float name="near_clip" value="{}"/><float name="far_clip" value="{}"/>
<transform name="to_world"><lookat origin="{}" target="{}" up="{}"/></transform>
<film type="hdrfilm"><integer name="width" value="{}"/><integer name="height" value="{}"/></film>
</sensor>
</scene>"#,
        p["fov"],
        p["fov_axis"].as_str().unwrap(),
        p["aperture_radius"],
        p["focus_distance"],
        p["near_clip"],
        p["far_clip"],
        v(&r["origin"]),
        v(&r["target"]),
        v(&r["up"]),
        r["film"][0],
        r["film"][1]
    );
    let loaded = load_str(&xml, Path::new("/virtual/thinlens.xml"), &[]).unwrap();
    let Camera::ThinLens(cam) = &loaded.camera else { panic!("not a thinlens camera") };
    let film = Vec2::new(r["film"][0].as_f64().unwrap() as f32, r["film"][1].as_f64().unwrap() as f32);
    let f = |a: &Value| a.as_f64().unwrap() as f32;
    let v3 = |a: &Value| Vec3::new(f(&a[0]), f(&a[1]), f(&a[2]));
    for ray in r["rays"].as_array().unwrap() {
        let film_pos = Vec2::new(f(&ray["film"][0]), f(&ray["film"][1])) * film;
        let u = Vec2::new(f(&ray["aperture"][0]), f(&ray["aperture"][1]));
        let got = cam.ray(film_pos, u);
        let (o, d) = (v3(&ray["o"]), v3(&ray["d"]));
        assert!((got.o - o).abs().max_element() < 2e-5, "origin {:?} vs Mitsuba {o:?}", got.o);
        assert!((got.d - d).abs().max_element() < 2e-6, "direction {:?} vs Mitsuba {d:?}", got.d);
        assert!((got.maxt / f(&ray["maxt"]) - 1.0).abs() < 1e-5, "maxt {} vs Mitsuba {}", got.maxt, ray["maxt"]);
        assert_eq!(f(&ray["weight"]), 1.0);
    }
}
