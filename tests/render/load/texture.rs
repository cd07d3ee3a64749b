//! `<texture>` (§2, §11): `bitmap` as a nested and a referenced reflectance, `checkerboard` values
//! (`eval`, and `eval_1` as a `mask` opacity and as a matte model's parameter), `rawconstant`, and
//! the textures' errors.

use std::path::Path;

use glam::{Vec2, Vec3};
use matte_render::bsdf::{Bsdf, Bxdf, Diffuse, Matte};
use matte_render::geometry::Ray;
use matte_render::load::{LoadedScene, load_str};
use matte_render::shape::SurfaceInteraction;
use matte_render::texture::Texture;

use super::references::{
    BITMAP_BILINEAR_CENTRE, BITMAP_NEAREST, BITMAP_RAW_CLAMP, CHECKERBOARD_DEFAULTS, CHECKERBOARD_EVAL,
    CHECKERBOARD_MEAN, CHECKERBOARD_SCALED, RAWCONSTANT_FLOAT, RAWCONSTANT_VECTOR,
};
use super::{FILE, assert_body_err, assert_vec, load, ok, temp_dir, with_sensor};
use crate::common::{SENSOR, assert_err_at, assert_error_at, scene};

fn write_png(path: &Path, w: u32, h: u32, rgb: &[u8]) {
    image::RgbImage::from_raw(w, h, rgb.to_vec()).unwrap().save(path).unwrap();
}

#[test]
fn bitmap_reflectance_nested_and_referenced() {
    let dir = temp_dir("bitmap");
    // 2×2: red, green / blue, grey 128 (first row = v in [0, 0.5), §11).
    write_png(&dir.join("tex.png"), 2, 2, &[255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128]);
    let path = dir.join("scene.xml");
    let xml = with_sensor(
        "<texture type=\"bitmap\" id=\"t\"><string name=\"filename\" value=\"tex.png\"/></texture>\
         <bsdf type=\"diffuse\" id=\"a\"><ref name=\"reflectance\" id=\"t\"/></bsdf>\
         <bsdf type=\"oren_nayar\" id=\"b\"><texture type=\"bitmap\" name=\"reflectance\"><string name=\"filename\" value=\"tex.png\"/>\
         <string name=\"filter_type\" value=\"nearest\"/></texture></bsdf>\
         <bsdf type=\"diffuse\" id=\"c\"><texture type=\"bitmap\" name=\"reflectance\"><string name=\"filename\" value=\"tex.png\"/>\
         <boolean name=\"raw\" value=\"true\"/><string name=\"filter_type\" value=\"nearest\"/><string name=\"wrap_mode\" value=\"clamp\"/></texture></bsdf>",
    );
    let s = load_str(&xml, &path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let tex = |i: usize| match &s.scene.bsdfs[i] {
        Bsdf::Diffuse(Diffuse { reflectance: Texture::Bitmap(t) })
        | Bsdf::Matte(Matte { reflectance: Texture::Bitmap(t), .. }) => t.clone(),
        other => panic!("{other:?}"),
    };
    // §11: 8-bit PNG is sRGB → 128 decodes to 0.215861; bilinear averages the LINEAR texels:
    // the centre of red, green, blue and grey 128 is 0.303965 [verified]. Mitsuba's:
    // `BITMAP_BILINEAR_CENTRE`, `BITMAP_NEAREST`, `BITMAP_RAW_CLAMP`.
    assert_vec(tex(0).eval(Vec2::splat(0.5)), BITMAP_BILINEAR_CENTRE.into(), 1e-5);
    // Nearest: v = 0 is the first row (red at the top left), grey 0.215861 at the bottom right;
    // repeat wrap (default): u + 1 is the same texel.
    let t = tex(1);
    for (&(uv, want), tol) in BITMAP_NEAREST.iter().zip([1e-6, 1e-6, 1e-6, 1e-5, 1e-6]) {
        assert_vec(t.eval(Vec2::from(uv)), want.into(), tol);
    }
    // raw: value/255, no decode; clamp wrap.
    let t = tex(2);
    for &(uv, want) in BITMAP_RAW_CLAMP {
        assert_vec(t.eval(Vec2::from(uv)), want.into(), 1e-6);
    }
}

/// `src/textures/checkerboard.cpp`: color0 where frac(u') and frac(v') are both > 1/2 or both
/// ≤ 1/2, color1 otherwise (uv' = to_uv·uv); defaults 0.4 and 0.2. Mitsuba's:
/// `CHECKERBOARD_SCALED`, `CHECKERBOARD_DEFAULTS`.
#[test]
fn checkerboard_texture() {
    let xml = |tex: &str| {
        scene(&format!("{SENSOR}\n<shape type=\"rectangle\"><bsdf type=\"diffuse\">\n{tex}\n</bsdf></shape>"))
    };
    let reflectance_at = |s: &LoadedScene, x: f32, y: f32| -> Vec3 {
        let si = s.scene.intersect(&Ray::new(Vec3::new(x, y, 1.0), Vec3::NEG_Z, f32::INFINITY)).expect("hit");
        match s.scene.bsdf(&si) {
            Bsdf::Diffuse(d) => d.reflectance.eval(si.uv),
            other => panic!("{other:?}"),
        }
    };
    // The rectangle's uv is ((x+1)/2, (y+1)/2); with to_uv = scale 2, uv' = (x+1, y+1).
    let s = load(&xml(r#"<texture type="checkerboard" name="reflectance"><rgb name="color0" value="0.9"/><rgb name="color1" value="0.1, 0.2, 0.3"/><transform name="to_uv"><scale x="2" y="2"/></transform></texture>"#)).unwrap();
    for &(x, y, expect) in CHECKERBOARD_SCALED {
        let (got, expect) = (reflectance_at(&s, x, y), Vec3::from(expect));
        assert!((got - expect).length() < 1e-6, "({x}, {y}): {got}, expected {expect}");
    }
    let d = load(&xml(r#"<texture type="checkerboard" name="reflectance"/>"#)).unwrap();
    for &(x, y, expect) in CHECKERBOARD_DEFAULTS {
        assert!((reflectance_at(&d, x, y) - Vec3::from(expect)).length() < 1e-6, "({x}, {y})");
    }
    let bad =
        xml("<texture type=\"checkerboard\" name=\"reflectance\"><float name=\"colour0\" value=\"0.5\"/></texture>");
    assert_err_at(load(&bad), Path::new(FILE), 4, "colour0");
    let textured = xml(
        "<texture type=\"checkerboard\" name=\"reflectance\"><texture type=\"checkerboard\" name=\"color0\"/></texture>",
    );
    assert_err_at(load(&textured), Path::new(FILE), 4, "\"color0\" must be a colour");
}

/// `src/textures/checkerboard.cpp`, `eval_1` (scalar parameters: roughness, opacity, …): the
/// opposite test of `eval`, color0 where frac(u') and frac(v') are on different sides of 1/2;
/// each colour's `eval_1` is its channel mean (`src/spectra/srgb.cpp`), and `mean()` is the
/// average of both. (Mitsuba 3.9.1 gives 0.3 at uv (0.25, 0.25) and 0.4 at (0.75, 0.25) for
/// color0 = (0.9, 0.1, 0.2), color1 = 0.3: `CHECKERBOARD_EVAL`, `CHECKERBOARD_MEAN`.)
#[test]
fn checkerboard_eval_1_swaps_the_colours() {
    let xml = scene(&format!(
        "{SENSOR}\n<shape type=\"rectangle\"><bsdf type=\"mask\"><texture type=\"checkerboard\" name=\"opacity\"><rgb name=\"color0\" value=\"0.9, 0.1, 0.2\"/><float name=\"color1\" value=\"0.3\"/></texture><bsdf type=\"diffuse\"/></bsdf></shape>"
    ));
    let s = load(&xml).unwrap();
    let si = s.scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, f32::INFINITY)).expect("hit");
    let Bsdf::Mask(m) = s.scene.bsdf(&si) else { panic!("expected a mask") };
    for &(uv, eval, eval_1) in CHECKERBOARD_EVAL {
        let uv = Vec2::from(uv);
        assert!((m.opacity.eval(uv) - Vec3::from(eval)).length() < 1e-6, "eval at {uv}");
        assert!((m.opacity.eval_1(uv) - eval_1).abs() < 1e-6, "eval_1 at {uv}: {}", m.opacity.eval_1(uv));
    }
    assert!((m.opacity.mean() - CHECKERBOARD_MEAN).abs() < 1e-6);
}

/// Mitsuba 3.9.1's `Checkerboard::eval_1` (what a scalar parameter reads) takes `color0` where
/// `eval` takes `color1`: at uv = (0.25, 0.25) both fractional parts are ≤ ½, `eval` gives
/// color0 but `eval_1` gives color1 (`src/textures/checkerboard.cpp`).
#[test]
fn checkerboard_parameter_follows_mitsubas_eval_1() {
    // A rectangle's `bsdf`, evaluated at `uv` for one pair of directions.
    let eval_at = |bsdf: &str, uv: Vec2| {
        let s = ok(&with_sensor(&format!("<shape type=\"rectangle\">{bsdf}</shape>")));
        let (wi, wo) = (Vec3::new(0.2, 0.1, 0.97).normalize(), Vec3::new(-0.5, 0.3, 0.8).normalize());
        s.scene.bsdfs[0].eval_pdf(&SurfaceInteraction::at_uv(uv), wi, wo).0
    };
    let textured = r#"<bsdf type="oren_nayar"><texture type="checkerboard" name="sigma"><float name="color0" value="0"/><float name="color1" value="1"/></texture></bsdf>"#;
    let sigma = |v: f64| format!(r#"<bsdf type="oren_nayar"><float name="sigma" value="{v}"/></bsdf>"#);
    let at = |uv| eval_at(textured, uv);
    let (one, zero) = (eval_at(&sigma(1.0), Vec2::ZERO), eval_at(&sigma(0.0), Vec2::ZERO));
    assert!(((at(Vec2::new(0.25, 0.25)) - one).abs()).max_element() < 1e-6);
    assert!(((at(Vec2::new(0.75, 0.25)) - zero).abs()).max_element() < 1e-6);
}

/// `src/spectra/rawconstant.cpp`: `value` as a float (every channel) or a vector, unconverted
/// (Mitsuba's: `RAWCONSTANT_VECTOR`, `RAWCONSTANT_FLOAT`).
#[test]
fn rawconstant_texture() {
    let xml = |tex: &str| {
        scene(&format!("{SENSOR}\n<shape type=\"rectangle\"><bsdf type=\"diffuse\">\n{tex}\n</bsdf></shape>"))
    };
    let refl = |s: &LoadedScene| {
        let si = s.scene.intersect(&Ray::new(Vec3::new(0.1, 0.2, 1.0), Vec3::NEG_Z, f32::INFINITY)).unwrap();
        match s.scene.bsdf(&si) {
            Bsdf::Diffuse(d) => d.reflectance.eval(si.uv),
            other => panic!("{other:?}"),
        }
    };
    let v = load(&xml(
        r#"<texture type="rawconstant" name="reflectance"><vector name="value" value="0.5, 0.25, 1"/></texture>"#,
    ))
    .unwrap();
    assert_eq!(refl(&v), Vec3::from(RAWCONSTANT_VECTOR));
    let f = load(&xml(r#"<texture type="rawconstant" name="reflectance"><float name="value" value="0.3"/></texture>"#))
        .unwrap();
    assert_eq!(refl(&f), Vec3::from(RAWCONSTANT_FLOAT));
    assert_err_at(
        load(&xml(r#"<texture type="rawconstant" name="reflectance"/>"#)),
        Path::new(FILE),
        4,
        "missing required parameter \"value\"",
    );
    assert_err_at(
        load(&xml(r#"<texture type="rawconstant" name="reflectance"><rgb name="value" value="0.5"/></texture>"#)),
        Path::new(FILE),
        4,
        "expected float or vector",
    );
}

#[test]
fn texture_errors() {
    let dir = temp_dir("texture_errors");
    write_png(&dir.join("ok.png"), 1, 1, &[10, 20, 30]);
    std::fs::write(dir.join("broken.png"), b"not a png").unwrap();
    let path = dir.join("scene.xml");
    let tex = |inner: &str| {
        with_sensor(&format!(
            "<bsdf type=\"diffuse\">\n<texture type=\"bitmap\" name=\"reflectance\">\n{inner}\n</texture>\n</bsdf>"
        ))
    };
    let check = |inner: &str, line: u32, needle: &str| match load_str(&tex(inner), &path, &[]) {
        Ok(_) => panic!("{inner}: expected an error"),
        Err(e) => assert_error_at(&e, &path, line + 2, needle),
    };
    check("<string name=\"filename\" value=\"missing.png\"/>", 3, "missing.png");
    check("<string name=\"filename\" value=\"broken.png\"/>", 3, "broken.png");
    check("", 2, "missing property \"filename\"");
    check(
        "<string name=\"filename\" value=\"ok.png\"/>\n<string name=\"filter_type\" value=\"cubic\"/>",
        4,
        "filter_type",
    );
    check("<string name=\"filename\" value=\"ok.png\"/>\n<string name=\"wrap_mode\" value=\"zero\"/>", 4, "wrap_mode");
    check(
        "<string name=\"filename\" value=\"ok.png\"/>\n<float name=\"gamma\" value=\"2.2\"/>",
        4,
        "unreferenced property \"gamma\"",
    );
    // A volume texture needs its volume (tests/render/volume_texture.rs has the rest); unknown
    // types are refused.
    assert_body_err(
        "<bsdf type=\"diffuse\">\n<texture type=\"volume\" name=\"reflectance\"/>\n</bsdf>",
        2,
        "missing property \"volume\"",
    );
    assert_body_err("<texture type=\"voronoi\"/>", 1, "unsupported texture type \"voronoi\"");
    // Given twice: as a property and as a texture (the parser rejects the duplicate name).
    let both = tex("<string name=\"filename\" value=\"ok.png\"/>")
        .replace("<bsdf type=\"diffuse\">\n", "<bsdf type=\"diffuse\">\n<float name=\"reflectance\" value=\"0.5\"/>");
    let Err(e) = load_str(&both, &path, &[]) else { panic!("expected an error") };
    assert!(e.to_string().starts_with(&format!("{}:", path.display())) && e.to_string().contains("reflectance"), "{e}");
}
