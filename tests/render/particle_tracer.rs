//! Mitsuba's `ptracer` (`src/integrators/ptracer.cpp`, docs/renderer-semantics.md §7):
//! light paths splatted to the film through the camera's importance. Oracles: closed forms
//! (an emitter filling the view renders its radiance; a diffuse plane under a point light
//! renders ρ/π·I·cos θ/d², integrated over each pixel's footprint numerically), and the
//! loader's documented defaults and refusals.

use glam::Vec3;
use matte_render::integrator::Integrator;
use matte_render::load::{LoadedScene, load_str};
use matte_render::renderer::render;
use std::f32::consts::PI;
use std::path::Path;

fn load(xml: &str) -> LoadedScene {
    load_str(xml, Path::new("/virtual/ptracer.xml"), &[]).unwrap_or_else(|e| panic!("{e}"))
}

fn scene(integrator: &str, body: &str, w: u32, h: u32, spp: u32) -> String {
    format!(
        r#"<scene version="3.0.0">
<integrator type="ptracer">{integrator}</integrator>
<sensor type="perspective"><float name="fov" value="40"/>
<transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
<sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler>
<film type="hdrfilm"><integer name="width" value="{w}"/><integer name="height" value="{h}"/><rfilter type="box"/></film>
</sensor>
{body}
</scene>"#
    )
}

/// A one-sided emitter filling the view, max_depth 1 (visible emitters only): every pixel's
/// expectation is the radiance (~2.5 % noise per pixel at this sample count).
#[test]
fn an_emitter_filling_the_view_renders_its_radiance() {
    let l = Vec3::new(0.2, 0.4, 0.6);
    let s = load(&scene(
        r#"<integer name="max_depth" value="1"/>"#,
        r#"<shape type="rectangle"><transform name="to_world"><scale value="2"/></transform>
           <emitter type="area"><rgb name="radiance" value="0.2, 0.4, 0.6"/></emitter></shape>"#,
        8,
        6,
        4096,
    ));
    let (img, stats) = render(&s.scene, &s.integrator, &s.camera, s.film, s.sampling.with_seed(1), &|_, _| {});
    assert_eq!(stats.invalid_samples, 0);
    let mut mean = Vec3::ZERO;
    for y in 0..6 {
        for x in 0..8 {
            let v = img.get(x, y);
            assert!((v - l).abs().max_element() < 0.08 * l.max_element(), "pixel ({x}, {y}): {v} vs {l}");
            mean += v / 48.0;
        }
    }
    assert!((mean - l).abs().max_element() < 0.01 * l.max_element(), "mean {mean} vs {l}");
}

/// A diffuse plane (ρ = 0.5) under a point light (I = 10 at height 2 above the origin, the
/// camera 4 above): L(x) = ρ/π · I · cos θ/d², averaged over each pixel's footprint (8×8
/// pixel-centred sub-samples). max_depth 2 is direct lighting only.
#[test]
fn a_plane_under_a_point_light_matches_the_closed_form() {
    let (w, h) = (8u32, 6u32);
    let s = load(&scene(
        r#"<integer name="max_depth" value="2"/>"#,
        r#"<shape type="rectangle"><transform name="to_world"><scale value="10"/></transform>
           <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
           <emitter type="point"><point name="position" x="0" y="0" z="2"/><rgb name="intensity" value="10"/></emitter>"#,
        w,
        h,
        32768,
    ));
    let (img, _) = render(&s.scene, &s.integrator, &s.camera, s.film, s.sampling.with_seed(3), &|_, _| {});
    let cam = &s.camera;
    let closed_form = |px: f32, py: f32| -> f32 {
        let r = cam.ray(glam::Vec2::new(px, py));
        let t = -r.o.z / r.d.z;
        let p = r.o + r.d * t;
        let to_light = Vec3::new(0.0, 0.0, 2.0) - p;
        let d2 = to_light.length_squared();
        0.5 / PI * 10.0 * (to_light.z / d2.sqrt()) / d2
    };
    let (mut worst, mut sum_got, mut sum_expected) = (0.0f32, 0.0f32, 0.0f32);
    for y in 0..h {
        for x in 0..w {
            let n = 8;
            let mut expected = 0.0;
            for j in 0..n {
                for i in 0..n {
                    expected +=
                        closed_form(x as f32 + (i as f32 + 0.5) / n as f32, y as f32 + (j as f32 + 0.5) / n as f32);
                }
            }
            expected /= (n * n) as f32;
            let got = img.get(x, y).x;
            worst = worst.max((got / expected - 1.0).abs());
            // ~2 % noise per pixel at this sample count.
            assert!((got / expected - 1.0).abs() < 0.08, "pixel ({x}, {y}): {got} vs {expected}");
            sum_got += got;
            sum_expected += expected;
        }
    }
    println!("ptracer point light: worst relative deviation {worst:.4}, image mean ratio {}", sum_got / sum_expected);
    assert!((sum_got / sum_expected - 1.0).abs() < 0.01, "image mean ratio {}", sum_got / sum_expected);
}

/// Defaults (max_depth −1, rr_depth 5, hide_emitters false) and what matte's ptracer
/// refuses: other filters than box, environment emitters, refracting BSDFs.
#[test]
fn ptracer_defaults_and_refusals() {
    let s = load(&scene("", "<emitter type=\"point\"/>", 4, 2, 4));
    let Integrator::ParticleTracer(pt) = &s.integrator else { panic!("not ptracer") };
    assert_eq!((pt.max_depth, pt.rr_depth, pt.hide_emitters), (u32::MAX, 5, false));
    let err = |xml: String| match load_str(&xml, Path::new("/virtual/ptracer.xml"), &[]) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e.to_string(),
    };
    let e = err(scene("", "<emitter type=\"constant\"/>", 4, 2, 4));
    assert!(e.starts_with("/virtual/ptracer.xml:2:") && e.contains("point, spot and projector"), "{e}");
    let e =
        err(scene("", "<emitter type=\"point\"/><shape type=\"sphere\"><bsdf type=\"dielectric\"/></shape>", 4, 2, 4));
    assert!(e.contains("refracting"), "{e}");
    let gaussian = scene("", "<emitter type=\"point\"/>", 4, 2, 4).replace("<rfilter type=\"box\"/>", "");
    assert!(err(gaussian).contains("box reconstruction filter"));
}
