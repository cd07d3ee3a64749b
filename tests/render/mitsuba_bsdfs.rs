//! `plastic`, `roughplastic`, `roughdielectric`, `thindielectric`, `normalmap`, `principled`,
//! `principledthin`, `mask`, `blendbsdf` and named conductor materials against the real Mitsuba 3.9.1: each configuration is one XML `<bsdf>` loaded by matte's scene loader and
//! by Mitsuba (`mitsuba_bsdfs/generate_reference.py` wrote the expected eval/pdf/sample
//! values once; see `mitsuba_bsdfs/reference.rs`). Plus the sampling checks that need no
//! oracle: sample weight = eval/pdf, Mitsuba's χ² test of the sampled directions against the
//! pdf, and the Dirac lobes' probabilities.

#[allow(clippy::excessive_precision)] // generated data: Mitsuba's values printed in full
#[path = "mitsuba_bsdfs/bumpmap/reference.rs"]
mod bumpmap_reference;
#[rustfmt::skip] // generated data, one configuration per line
#[allow(clippy::excessive_precision)] // generated data: Mitsuba's values printed in full
mod reference;

use crate::common::{Pcg32, PcgExt, chi2_render_bsdf, sidak};
use glam::{Vec2, Vec3};
use matte_render::bsdf::{Bsdf, Bxdf};
use matte_render::load::load_str;
use matte_render::shape::SurfaceInteraction;
use reference::CONFIGS;
use std::path::Path;

const SENSOR: &str = r#"<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="2"/></film></sensor>"#;

/// The BSDF of a one-`<bsdf>` scene, built by the scene loader.
fn load_bsdf(xml: &str) -> Bsdf {
    let scene = format!("<scene version=\"3.0.0\">\n{SENSOR}\n{xml}\n</scene>");
    let loaded = load_str(&scene, Path::new("/virtual/bsdf.xml"), &[]).unwrap_or_else(|e| panic!("{e}\n{scene}"));
    loaded.scene.bsdfs.into_iter().next().expect("one bsdf")
}

/// |a − b| relative to `scale` (the row's largest expected magnitude, so that tiny channels of
/// a bright value are compared at the value's precision).
fn rel_err(a: f32, b: f32, scale: f32) -> f32 {
    if a == b { 0.0 } else { (a - b).abs() / scale.max(b.abs()).max(1e-30) }
}

#[test]
fn eval_and_pdf_match_mitsuba() {
    let mut report = Vec::new();
    for c in CONFIGS {
        let bsdf = load_bsdf(c.xml);
        let (mut max_f, mut max_p) = (0.0f32, 0.0f32);
        for &(wi, wo, f_ref, p_ref) in c.eval {
            let (wi, wo, f_ref) = (Vec3::from(wi), Vec3::from(wo), Vec3::from(f_ref));
            let (f, p) = bsdf.eval_pdf(&SurfaceInteraction::at_uv(Vec2::ZERO), wi, wo);
            let scale = f_ref.max_element();
            let ef = (0..3).map(|k| rel_err(f[k], f_ref[k], scale)).fold(0.0, f32::max);
            let ep = rel_err(p, p_ref, 0.0);
            assert!(ef < 2e-4, "{}: eval({wi}, {wo}) = {f}, Mitsuba {f_ref} (rel {ef})", c.name);
            assert!(ep < 2e-4, "{}: pdf({wi}, {wo}) = {p}, Mitsuba {p_ref} (rel {ep})", c.name);
            max_f = max_f.max(ef);
            max_p = max_p.max(ep);
        }
        report.push(format!("{:34} max rel diff eval {max_f:.2e} pdf {max_p:.2e}", c.name));
    }
    println!("{}", report.join("\n"));
}

/// Smooth plastic, thin dielectric, smooth conductors and normal-mapped versions of these or of
/// `diffuse` sample deterministically from the same numbers as
/// Mitsuba (lobe by `sample1`, Mitsuba's cosine warp), so their samples must agree.
#[test]
fn samples_match_mitsuba() {
    let mut checked = 0;
    for c in CONFIGS.iter().filter(|c| !c.sample.is_empty()) {
        let bsdf = load_bsdf(c.xml);
        let mut max_err = 0.0f32;
        for &(wi, s1, s2, wo_ref, w_ref, p_ref) in c.sample {
            let (wi, wo_ref, w_ref) = (Vec3::from(wi), Vec3::from(wo_ref), Vec3::from(w_ref));
            let Some(s) = bsdf.sample(&SurfaceInteraction::at_uv(Vec2::ZERO), wi, s1, Vec2::from(s2)) else {
                assert!(w_ref == Vec3::ZERO, "{}: no sample for wi {wi}, Mitsuba weight {w_ref}", c.name);
                continue;
            };
            let e = (s.wo - wo_ref).abs().max_element();
            let ew = (0..3).map(|k| rel_err(s.weight[k], w_ref[k], w_ref.max_element())).fold(0.0, f32::max);
            let ep = rel_err(s.pdf, p_ref, 0.0);
            assert!(
                e < 1e-5 && ew < 1e-4 && ep < 1e-4,
                "{}: wi {wi} u ({s1}, {s2:?}): {s:?} vs Mitsuba wo {wo_ref} weight {w_ref} pdf {p_ref}",
                c.name
            );
            max_err = max_err.max(ew).max(ep);
            checked += 1;
        }
        println!("{:34} samples: max rel diff {max_err:.2e}", c.name);
    }
    assert!(checked > 80);
}

/// Uniform direction on the sphere.
fn sphere(rng: &mut Pcg32) -> Vec3 {
    let z = 2.0 * rng.next_f32() - 1.0;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * rng.next_f32();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Whether the configuration transmits (then wi is drawn on both sides).
/// (A principled BSDF without `spec_trans` samples nothing from below, while Mitsuba's pdf
/// there is that of a reflection lobe whose value is 0: such directions are left out.)
fn two_sided(c: &reference::Config) -> bool {
    c.name.contains("dielectric")
        || c.name.starts_with("principledthin")
        || (c.name.starts_with("principled") && c.xml.contains("spec_trans"))
}

#[test]
fn sample_weight_is_eval_over_pdf() {
    let mut rng = Pcg32::new(5, 17);
    for c in CONFIGS {
        let bsdf = load_bsdf(c.xml);
        let (mut smooth, mut delta) = (0, 0);
        for _ in 0..4000 {
            let mut wi = sphere(&mut rng);
            if !two_sided(c) {
                wi.z = wi.z.abs();
            }
            let Some(s) = bsdf.sample(&SurfaceInteraction::at_uv(Vec2::ZERO), wi, rng.next_f32(), rng.next_vec2())
            else {
                continue;
            };
            assert!(s.weight.is_finite() && s.weight.min_element() >= 0.0 && s.pdf > 0.0, "{}: {s:?}", c.name);
            assert!((s.wo.length() - 1.0).abs() < 1e-4, "{}: {s:?}", c.name);
            if s.delta {
                delta += 1;
                continue;
            }
            smooth += 1;
            let (f, p) = bsdf.eval_pdf(&SurfaceInteraction::at_uv(Vec2::ZERO), wi, s.wo);
            assert!((p - s.pdf).abs() <= 1e-3 * p.max(s.pdf), "{}: wi {wi} wo {}: pdf {} vs {p}", c.name, s.wo, s.pdf);
            // Mitsuba's roughdielectric without visible normals samples Walter's widened lobe
            // but weights the sample as if drawn from the unwidened D (its pdf is the widened
            // one): the weight is not eval/pdf there, in Mitsuba as in matte.
            if c.name.starts_with("roughdielectric") && c.xml.contains("sample_visible") {
                continue;
            }
            let expected = f / p;
            for k in 0..3 {
                assert!(
                    (s.weight[k] - expected[k]).abs() <= 2e-3 * expected.max_element().max(1e-3),
                    "{}: wi {wi} wo {}: weight {} vs eval/pdf {expected}",
                    c.name,
                    s.wo,
                    s.weight
                );
            }
        }
        let pure_delta = c.name.starts_with("thin") || c.name.starts_with("conductor_");
        // A mask's pass-through and a plastic's specular lobe (also inside a blend) are Dirac.
        let has_delta = pure_delta
            || c.name.starts_with("plastic")
            || c.name.starts_with("normalmap_plastic")
            || c.name.starts_with("mask_")
            || c.name == "blend_diffuse_plastic";
        assert_eq!(delta > 0, has_delta, "{}: {delta} Dirac samples", c.name);
        assert_eq!(smooth > 0, !pure_delta, "{}: {smooth} smooth samples", c.name);
    }
}

/// (configuration, incidence in degrees; > 90° is from below). Each sampling code path once,
/// dielectrics from both sides; the rest is left out to keep the file fast (smooth-only BSDFs
/// have nothing to histogram; rough conductors are covered in `specular_bsdfs.rs`).
const CHI2_RUNS: &[(&str, f64)] = &[
    ("plastic_coloured", 45.0),
    ("roughplastic_ggx", 45.0),
    ("roughplastic_beckmann_plain", 45.0),
    ("roughdielectric_default", 10.0),
    ("roughdielectric_default", 130.0),
    ("roughdielectric_ggx", 10.0),
    ("roughdielectric_aniso_plain", 130.0),
    ("roughdielectric_beckmann_tinted", 130.0),
    ("normalmap_roughconductor", 45.0),
    ("principled_full", 45.0),
    ("principled_glass", 10.0),
    ("principled_rates", 130.0),
    ("principledthin_full", 10.0),
    ("principledthin_rates", 130.0),
];

#[test]
fn samples_follow_pdf_chi_square() {
    let level = sidak(CHI2_RUNS.len());
    let mut failures = Vec::new();
    for (seed, &(name, theta)) in CHI2_RUNS.iter().enumerate() {
        let c = CONFIGS.iter().find(|c| c.name == name).expect(name);
        let seed = 41 + seed as u64;
        let t = theta.to_radians();
        let wi = Vec3::new((t.sin() * 0.6f64.cos()) as f32, (t.sin() * 0.6f64.sin()) as f32, t.cos() as f32);
        // The refracted lobe of α = 0.1 is squeezed by η²: integrate the cells more finely.
        let ires = if c.name.starts_with("roughdielectric") { 24 } else { 12 };
        match chi2_render_bsdf(&load_bsdf(c.xml), &SurfaceInteraction::at_uv(Vec2::ZERO), wi, seed, ires) {
            Err(e) => failures.push(format!("{name} θ={theta}: {e}")),
            Ok(out) => {
                println!("{name:34} θ={theta:5}: p = {:.3e}", out.p_value);
                if out.p_value <= level {
                    failures.push(format!(
                        "{name} θ={theta}: p = {} (χ² {} / {} dof)",
                        out.p_value, out.statistic, out.dof
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Thin dielectric: the pane reflects R' = 2R/(1 + R) and transmits the rest along −wi;
/// R from the f64 Fresnel formula (bk7 over air by default).
#[test]
fn thin_dielectric_lobe_probabilities() {
    let bsdf = load_bsdf(r#"<bsdf type="thindielectric"/>"#);
    let eta = 1.5046f64 / 1.000277;
    for &cos_i in &[1.0f64, 0.7, 0.3, 0.05] {
        let sin_t = (1.0 - cos_i * cos_i).sqrt() / eta;
        let cos_t = (1.0 - sin_t * sin_t).sqrt();
        let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
        let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
        let r = 0.5 * (rs * rs + rp * rp);
        let r_pane = 2.0 * r / (1.0 + r);
        for side in [1.0f32, -1.0] {
            let wi = Vec3::new((1.0 - cos_i * cos_i).sqrt() as f32, 0.0, side * cos_i as f32);
            let refl =
                bsdf.sample(&SurfaceInteraction::at_uv(Vec2::ZERO), wi, (r_pane * 0.999) as f32, Vec2::ZERO).unwrap();
            let pass = bsdf
                .sample(&SurfaceInteraction::at_uv(Vec2::ZERO), wi, (r_pane * 1.001).min(0.9999) as f32, Vec2::ZERO)
                .unwrap();
            assert!((refl.pdf as f64 - r_pane).abs() < 1e-5, "cos {cos_i}: {} vs {r_pane}", refl.pdf);
            assert_eq!(refl.wo, Vec3::new(-wi.x, -wi.y, wi.z));
            assert_eq!(pass.wo, -wi);
            assert!(refl.delta && pass.delta && pass.eta == 1.0);
            assert!((pass.pdf as f64 - (1.0 - r_pane)).abs() < 1e-5);
        }
    }
}

/// Every `data/ior` table of the 3.9.1 wheel is a named material (71, incl. the one the
/// Mitsuba test scenes use, `a-C`); names are case-sensitive file names.
#[test]
fn every_mitsuba_conductor_material_is_known() {
    use matte_render::bsdf::{conductor_material, conductor_material_names};
    assert_eq!(conductor_material_names().count(), 71);
    for name in ["a-C", "Au", "Cr", "W", "TiO2-e_palik", "d-C", "Se-e", "none"] {
        let (eta, k) = conductor_material(name).unwrap_or_else(|e| panic!("{e}"));
        assert!(eta.is_finite() && k.is_finite() && eta.min_element() >= 0.0 && k.min_element() >= 0.0, "{name}");
    }
    assert!(conductor_material("au").unwrap_err().contains("a-C"));
}

/// Bad input for the new plugins: one-line errors at `file:line`, never a panic. `body`
/// starts on line 3 of the scene (after `<scene>` and the sensor).
#[test]
fn bad_parameters_are_errors_at_file_and_line() {
    let cases: &[(&str, u32, &str)] = &[
        ("<bsdf type=\"plastic\">\n<float name=\"roughness\" value=\"0.1\"/>\n</bsdf>", 4, "roughness"),
        ("<bsdf type=\"plastic\">\n<string name=\"int_ior\" value=\"unobtainium\"/>\n</bsdf>", 4, "unknown IOR name"),
        (
            "<bsdf type=\"plastic\">\n<rgb name=\"diffuse_reflectance\" value=\"1.5, 0.2, 0.2\"/>\n</bsdf>",
            4,
            "diffuse_reflectance",
        ),
        (
            "<bsdf type=\"roughplastic\">\n<float name=\"alpha_u\" value=\"0.1\"/>\n<float name=\"alpha_v\" value=\"0.2\"/>\n</bsdf>",
            4,
            "anisotropic",
        ),
        (
            "<bsdf type=\"roughplastic\">\n<string name=\"distribution\" value=\"phong\"/>\n</bsdf>",
            4,
            "beckmann or ggx",
        ),
        ("<bsdf type=\"roughplastic\">\n<float name=\"int_ior\" value=\"1.000277\"/>\n</bsdf>", 4, "must differ"),
        ("<bsdf type=\"roughdielectric\">\n<float name=\"alpha\" value=\"-0.1\"/>\n</bsdf>", 4, "roughness"),
        (
            "<bsdf type=\"roughdielectric\">\n<float name=\"alpha\" value=\"0.1\"/>\n<float name=\"alpha_u\" value=\"0.1\"/>\n</bsdf>",
            3,
            "given together",
        ),
        (
            "<bsdf type=\"roughplastic\">\n<texture type=\"bitmap\" name=\"alpha\"/>\n</bsdf>",
            3,
            "texture for \"alpha\"",
        ),
        ("<bsdf type=\"roughdielectric\">\n<texture type=\"bitmap\" name=\"alpha\"/>\n</bsdf>", 4, "filename"),
        ("<bsdf type=\"thindielectric\">\n<float name=\"int_ior\" value=\"nan\"/>\n</bsdf>", 4, "int_ior"),
        (
            "<bsdf type=\"conductor\">\n<string name=\"material\" value=\"Gold\"/>\n</bsdf>",
            4,
            "unknown conductor material \"Gold\"",
        ),
        (
            "<bsdf type=\"normalmap\">\n<rgb name=\"normalmap\" value=\"0.5, 0.5, 1\"/>\n</bsdf>",
            3,
            "exactly one nested BSDF",
        ),
        ("<bsdf type=\"normalmap\">\n<bsdf type=\"diffuse\"/>\n</bsdf>", 3, "missing the \"normalmap\" texture"),
        (
            "<bsdf type=\"normalmap\">\n<rgb name=\"normalmap\" value=\"0.5, 0.5, 1\"/>\n<bsdf type=\"diffuse\"/>\n<float name=\"scale\" value=\"2\"/>\n</bsdf>",
            6,
            "scale",
        ),
        ("<bsdf type=\"twosided\">\n<bsdf type=\"roughdielectric\"/>\n</bsdf>", 3, "transmissive"),
    ];
    for &(body, line, needle) in cases {
        let scene = format!("<scene version=\"3.0.0\">\n{SENSOR}\n{body}\n</scene>");
        let e = match load_str(&scene, Path::new("/virtual/bsdf.xml"), &[]) {
            Ok(_) => panic!("expected an error containing {needle:?} for\n{body}"),
            Err(e) => e.to_string(),
        };
        assert!(!e.contains('\n'), "multi-line error: {e}");
        assert!(e.starts_with(&format!("/virtual/bsdf.xml:{line}:")), "expected line {line} in: {e}");
        assert!(e.contains(needle), "expected {needle:?} in: {e}");
    }
}

/// Odd parameter values for the new plugins: either a one-line error at `file:line`, or a
/// scene that renders without panics and without NaN/Inf samples.
#[test]
fn odd_values_never_panic_and_render_finite() {
    const TEMPLATES: &[&str] = &[
        r#"<bsdf type="plastic"><float name="int_ior" value="{v}"/></bsdf>"#,
        r#"<bsdf type="plastic"><float name="diffuse_reflectance" value="{v}"/><boolean name="nonlinear" value="true"/></bsdf>"#,
        r#"<bsdf type="roughplastic"><float name="alpha" value="{v}"/></bsdf>"#,
        r#"<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="ext_ior" value="{v}"/></bsdf>"#,
        r#"<bsdf type="roughdielectric"><float name="alpha" value="{v}"/></bsdf>"#,
        r#"<bsdf type="roughdielectric"><string name="distribution" value="ggx"/><float name="int_ior" value="{v}"/><boolean name="sample_visible" value="false"/></bsdf>"#,
        r#"<bsdf type="thindielectric"><float name="int_ior" value="{v}"/></bsdf>"#,
        r#"<bsdf type="normalmap"><rgb name="normalmap" value="{v}, 0.5, 0.5"/><bsdf type="roughplastic"/></bsdf>"#,
        r#"<bsdf type="principled"><float name="roughness" value="{v}"/><float name="spec_trans" value="0.5"/></bsdf>"#,
        r#"<bsdf type="principled"><float name="eta" value="{v}"/><float name="clearcoat" value="1"/></bsdf>"#,
        r#"<bsdf type="principled"><float name="specular" value="{v}"/><float name="metallic" value="0.5"/><float name="anisotropic" value="1"/></bsdf>"#,
        r#"<bsdf type="principled"><float name="main_specular_sampling_rate" value="{v}"/><float name="sheen" value="1"/></bsdf>"#,
        r#"<bsdf type="principledthin"><float name="eta" value="{v}"/><float name="spec_trans" value="1"/><float name="diff_trans" value="2"/></bsdf>"#,
        r#"<bsdf type="principledthin"><float name="roughness" value="{v}"/><float name="spec_trans" value="0.5"/></bsdf>"#,
    ];
    const VALUES: &[&str] = &["0", "-1", "1", "2", "1e-30", "1e30", "nan", "inf", "1e9"];
    let camera = r#"<sensor type="perspective"><float name="fov" value="60"/><transform name="to_world"><lookat origin="0,0,5" target="0,0,0"/></transform><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="2"/></film></sensor>"#;
    let (mut accepted, mut failures) = (0, Vec::new());
    for t in TEMPLATES {
        for v in VALUES {
            let bsdf = t.replace("{v}", v);
            let xml = format!(
                "<scene version=\"3.0.0\">\n{camera}<shape type=\"sphere\">{bsdf}</shape><shape type=\"sphere\"><transform name=\"to_world\"><translate z=\"-3\"/></transform></shape><emitter type=\"constant\"/><emitter type=\"point\"><point name=\"position\" value=\"0 3 3\"/></emitter>\n</scene>"
            );
            let loaded = std::panic::catch_unwind(|| load_str(&xml, Path::new("/virtual/odd.xml"), &[]))
                .unwrap_or_else(|_| panic!("panicked on {bsdf}"));
            let s = match loaded {
                Err(e) => {
                    let text = e.to_string();
                    assert!(text.starts_with("/virtual/odd.xml:") && !text.contains('\n'), "{bsdf}: {text}");
                    continue;
                }
                Ok(s) => s,
            };
            accepted += 1;
            let rendered = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                matte_render::renderer::render(
                    &s.scene,
                    &s.integrator,
                    &s.camera,
                    s.film.clone(),
                    s.sampling.with_spp(4).with_seed(0),
                    &|_, _| {},
                )
            }));
            match rendered {
                Err(_) => failures.push(format!("{bsdf}: the renderer panicked")),
                Ok((img, stats)) if stats.invalid_samples > 0 || !img.pixels.iter().all(|p| p.is_finite()) => {
                    failures.push(format!("{bsdf}: {} NaN/Inf samples", stats.invalid_samples))
                }
                Ok(_) => {}
            }
        }
    }
    assert!(failures.is_empty(), "accepted, but rendered NaN/Inf:\n{}", failures.join("\n"));
    assert!(accepted > TEMPLATES.len() * 3, "{accepted}");
}

/// `bumpmap` at the BSDF level: a generated 5×4 height
/// map, hits with explicit ∂p/∂u, ∂p/∂v, normals and shading frame, against Mitsuba 3.9.1
/// (`mitsuba_bsdfs/bumpmap/generate_reference.py`).
#[test]
fn bumpmap_matches_mitsuba_at_given_hit_geometry() {
    use bumpmap_reference::{HEIGHT, NESTED, ROWS, TEXELS, WIDTH};
    use matte_render::bsdf::bump_map::{BumpMap, HitGeometry};
    use matte_render::geometry::Frame;
    use matte_render::texture::Texture;
    use matte_render::texture::{BitmapOptions, BitmapTexture};
    use std::sync::Arc;
    let texels = TEXELS.iter().map(|&g| Vec3::splat(g)).collect();
    let height = Texture::Bitmap(Arc::new(
        BitmapTexture::from_linear(WIDTH, HEIGHT, texels, &BitmapOptions::default()).unwrap(),
    ));
    let maps: Vec<BumpMap<Bsdf>> = NESTED
        .iter()
        .map(|&(xml, scale)| BumpMap {
            height: height.clone(),
            nested: Box::new(load_bsdf(xml)),
            scale,
            flip_invalid_normals: true,
            use_shadowing_function: true,
        })
        .collect();
    let (mut max_f, mut max_p, mut nonzero) = (0.0f32, 0.0f32, 0);
    for &(k, n, s, t, sn, dp_du, dp_dv, uv, wi, wo, f_ref, p_ref) in ROWS {
        let g = HitGeometry {
            dp_du: Vec3::from(dp_du),
            dp_dv: Vec3::from(dp_dv),
            n: Vec3::from(n),
            sh_frame: Frame { s: Vec3::from(s), t: Vec3::from(t), n: Vec3::from(sn) },
        };
        let (f, p) =
            maps[k].eval_pdf_at(&SurfaceInteraction::at_uv(Vec2::from(uv)), &g, Vec3::from(wi), Vec3::from(wo));
        let f_ref = Vec3::from(f_ref);
        let ef = (0..3).map(|c| rel_err(f[c], f_ref[c], f_ref.max_element())).fold(0.0, f32::max);
        let ep = rel_err(p, p_ref, 0.0);
        assert!(
            ef < 1e-4 && ep < 1e-4,
            "config {k} uv {uv:?} wi {wi:?} wo {wo:?}: ({f}, {p}) vs Mitsuba ({f_ref}, {p_ref})"
        );
        max_f = max_f.max(ef);
        max_p = max_p.max(ep);
        nonzero += usize::from(p_ref > 0.0);
    }
    println!("bumpmap: max rel diff eval {max_f:.2e} pdf {max_p:.2e} over {} rows ({nonzero} non-zero)", ROWS.len());
    assert!(nonzero > 10);
}
