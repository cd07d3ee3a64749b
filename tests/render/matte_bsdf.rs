//! The renderer's Matte BSDF (`rust/render/src/bsdf/matte.rs`) as the loader builds it from
//! scene files (`rust/render/src/load/bsdf.rs`): textured parameters (a constant texture renders
//! as the number, refused forms name file:line; `docs/models.md#spatially-varying-parameters`),
//! a table file as `tabulated_brdf` (each RGB channel its own ρ, a missing file a one-line
//! error), and Mitsuba 0.6's `roughdiffuse` XML through the version upgrade. (Which colour of a
//! checkerboard a parameter reads, Mitsuba's `eval_1`, is checked with the other checkerboard
//! tests in `tests/render/load/texture.rs`.)

use crate::common::{direction, inner_values, model, models_from_defaults, table_of};
use glam::{Vec2, Vec3};
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue};
use matte_render::bsdf::{Bsdf, Bxdf, Matte};
use matte_render::load::load_str;
use matte_render::shape::SurfaceInteraction;
use std::f64::consts::PI;
use std::path::Path;

const FILE: &str = "/virtual/scenes/textured.xml";

fn scene(bsdf: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="direct"/>
  <sensor type="perspective">
    <transform name="to_world"><lookat origin="0,0,3" target="0,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <emitter type="directional"><vector name="direction" value="0.3,0.2,-1"/></emitter>
  <shape type="rectangle">
    {bsdf}
  </shape>
</scene>"#
    )
}

fn eval_at(xml: &str, uv: Vec2) -> Vec3 {
    let s = load_str(xml, Path::new(FILE), &[]).unwrap_or_else(|e| panic!("{e}"));
    let (wi, wo) = (Vec3::new(0.2, 0.1, 0.97).normalize(), Vec3::new(-0.5, 0.3, 0.8).normalize());
    s.scene.bsdfs[0].eval_pdf(&matte_render::shape::SurfaceInteraction::at_uv(uv), wi, wo).0
}

/// A texture whose value is the same everywhere gives the number's BSDF (the per-hit path is
/// the same kernel), and the scene then holds a `Matte` with textured parameters. Every numeric
/// parameter of every registered model, at the first of `common::inner_values` that the model
/// accepts with its other defaults and that is not its default.
#[test]
fn constant_texture_equals_the_number() {
    let mut checked = 0;
    for spec in models_from_defaults() {
        for p in spec.numeric() {
            let default = p.default_value();
            let v = inner_values(p)
                .into_iter()
                .find(|&x| {
                    Some(ParamValue::Number(x)) != default && DiffuseModel::with(spec.name, &[(p.name, x)]).is_ok()
                })
                .unwrap_or_else(|| panic!("{}.{}: no value to texture", spec.name, p.name));
            let tol: f32 = match spec.name {
                // Wolff's per-lane F_dr is its fitted average.
                "wolff" => 2e-4,
                // van Ginneken: the roughness axis (Hermite in m) against the table built for m = v.
                "ginneken" => 2e-3,
                _ => 1e-5,
            };
            let (kind, name) = (spec.name, p.name);
            let number = scene(&format!(r#"<bsdf type="{kind}"><float name="{name}" value="{v}"/></bsdf>"#));
            let textured = scene(&format!(
                r#"<bsdf type="{kind}"><texture type="checkerboard" name="{name}"><float name="color0" value="{v}"/><float name="color1" value="{v}"/></texture></bsdf>"#
            ));
            let s = load_str(&textured, Path::new(FILE), &[]).unwrap();
            assert!(matches!(&s.scene.bsdfs[0], Bsdf::Matte(m) if m.is_textured()), "{kind}: not a textured Matte");
            let (a, b) = (eval_at(&number, Vec2::new(0.3, 0.6)), eval_at(&textured, Vec2::new(0.3, 0.6)));
            assert!(((a - b).abs() / a).max_element() <= tol, "{kind} {name} = {v}: {a} vs {b}");
            checked += 1;
        }
    }
    assert!(checked >= 5, "only {checked} numeric parameters");
}

#[test]
fn refused_textures_name_file_and_line() {
    let cases = [
        (r#"<bsdf type="oren_nayar"><texture type="checkerboard" name="model"/></bsdf>"#, "not a numeric parameter"),
        (r#"<bsdf type="lambert"><texture type="checkerboard" name="sigma"/></bsdf>"#, "sigma"),
    ];
    for (bsdf, want) in cases {
        let e = load_str(&scene(bsdf), Path::new(FILE), &[]).err().expect("must fail").to_string();
        assert!(e.contains("textured.xml:9") && e.contains(want), "{bsdf}: {e}");
    }
}

/// `<bsdf type="tabulated_brdf">` in `matte render`'s loader: the file resolves next to the
/// scene, each RGB channel gets its own ρ, and a missing file is a one-line error at the
/// element's line.
#[test]
fn the_renderer_loads_a_table_file_as_a_bsdf() {
    let on = model("oren_nayar", &[("sigma", "0.3"), ("model", "full")]);
    let dir = std::env::temp_dir().join(format!("matte_tabulated_scene_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    table_of(&on).write(&dir.join("truth.json")).unwrap();
    let xml = |file: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n<bsdf type=\"tabulated_brdf\">\n\
             <string name=\"filename\" value=\"{file}\"/>\n<rgb name=\"reflectance\" value=\"0.2, 0.5, 0.75\"/></bsdf>\n</scene>"
        )
    };
    let scene = load_str(&xml("truth.json"), &dir.join("scene.xml"), &[]).unwrap();
    let bsdf = &scene.scene.bsdfs[0];
    let Bsdf::Matte(Matte { model: DiffuseModel::Tabulated(_), .. }) = bsdf else { panic!("{bsdf:?}") };
    let (wi, wo) = (direction(60f64.to_radians(), 0.0), direction(30f64.to_radians(), PI));
    let rho = Vec3::new(0.2, 0.5, 0.75);
    let (f_cos, pdf) = bsdf.eval_pdf(&SurfaceInteraction::at_uv(Vec2::ZERO), wi, wo);
    let want = on.eval(wi, wo, rho.to_array());
    for c in 0..3 {
        assert!((f_cos[c] / wo.z / want[c] - 1.0).abs() < 1e-4, "channel {c}: {} vs {}", f_cos[c] / wo.z, want[c]);
    }
    assert!((pdf - wo.z / std::f32::consts::PI).abs() < 1e-6);
    let e = load_str(&xml("absent.json"), &dir.join("scene.xml"), &[]).err().unwrap().to_string();
    assert!(e.contains("scene.xml:4") && e.contains("absent.json") && !e.contains('\n'), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn mitsuba_0_6_xml_loads_through_the_upgrade() {
    let xml = r#"<scene version="0.6.0">
<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="2"/></film></sensor>
<bsdf type="roughdiffuse"><float name="alpha" value="0.4"/><boolean name="useFastApprox" value="true"/></bsdf>
</scene>"#;
    let s = load_str(xml, Path::new("/virtual/scene.xml"), &[]).unwrap();
    let Bsdf::Matte(Matte { model, .. }) = &s.scene.bsdfs[0] else { panic!("{:?}", s.scene.bsdfs[0]) };
    assert_eq!(model.kind(), "roughdiffuse");
    assert_eq!(
        model.parameters(),
        vec![
            ("alpha", ParamValue::Number(0.4f32 as f64)),
            ("use_fast_approx", ParamValue::Flag(true)),
            ("sampling", ParamValue::Text("cosine".into()))
        ]
    );
}
