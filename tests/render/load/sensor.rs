//! `<sensor>`, `<film>`, `<rfilter>`, `<sampler>` (§4–§6): camera rays (perspective,
//! `orthographic`), the field of view, clip range, principal point and `to_world`, film size, crop
//! and filters, sampler defaults, and their errors.

use std::path::Path;

use glam::{Vec2, Vec3};
use matte_render::film::{CropWindow, ReconstructionFilter};
use matte_render::load::LoadedScene;

use super::references::{
    CAMERA_CENTRE, CAMERA_CORNER, CAMERA_OPPOSITE_CORNER, DEFAULT_FILM_SIZE, DEFAULT_X_FOV, FOV_45_PORTRAIT_TAN_HALF,
    FOV_45_X_FOV, NEAR_FAR_CENTRE, NEAR_FAR_CORNER, PLAIN_AT_SHIFTED_CENTRE, PRINCIPAL_POINT_CENTRE,
    TURNED_CAMERA_CENTRE,
};
use super::{FILE, assert_err, assert_vec, load, ok, with_sensor};
use crate::common::{SENSOR, assert_err_at, scene};

/// A perspective sensor with identity `to_world` (looking along +z) and the given extras.
fn camera(props: &str, width: u32, height: u32) -> LoadedScene {
    ok(&scene(&format!(
        "<sensor type=\"perspective\">{props}<film type=\"hdrfilm\"><integer name=\"width\" value=\"{width}\"/>\
         <integer name=\"height\" value=\"{height}\"/></film></sensor>"
    )))
}

/// tan(x_fov/2) seen through the ray at the middle of the left film edge of a camera with
/// identity `to_world` (docs/renderer-semantics.md §4: that ray is normalize((t, 0, 1))).
fn tan_half_x_fov(s: &LoadedScene) -> f32 {
    let h = s.film.height() as f32;
    let d = s.camera.ray(Vec2::new(0.0, h / 2.0)).d;
    assert!(d.y.abs() < 1e-6, "{d}");
    d.x / d.z
}

fn tan_half_deg(deg: f64) -> f32 {
    (deg.to_radians() / 2.0).tan() as f32
}

#[test]
fn camera_ray_matches_the_verified_example() {
    // §4: camera at (0,0,5) looking at the origin, fov 90, 4×2 film; corner (0,0) gives
    // d = (−0.667, 0.333, −0.667) (exactly (−2, 1, −2)/3: local (1, 1/2, 1)/1.5, local +x =
    // left = world −x), and the ray starts on the near plane: o = c + d·near/d_local.z; Mitsuba's
    // rays: `CAMERA_CORNER`, `CAMERA_CENTRE`, `CAMERA_OPPOSITE_CORNER`.
    let s = ok(&scene(
        "<sensor type=\"perspective\"><float name=\"fov\" value=\"90\"/>\
         <transform name=\"to_world\"><lookat origin=\"0,0,5\" target=\"0,0,0\" up=\"0,1,0\"/></transform>\
         <film type=\"hdrfilm\"><integer name=\"width\" value=\"4\"/><integer name=\"height\" value=\"2\"/></film></sensor>",
    ));
    let r = s.camera.ray(Vec2::ZERO);
    assert_vec(r.d, CAMERA_CORNER.d.into(), 1e-6);
    assert_vec(r.o, CAMERA_CORNER.o.into(), 1e-6);
    // maxt = (far − near)/d_local.z with the defaults 0.01 and 10000.
    assert!((r.maxt - CAMERA_CORNER.maxt).abs() < 2e-3, "{}", r.maxt);
    // The centre looks at the target; the opposite corner mirrors the first.
    let c = s.camera.ray(Vec2::new(2.0, 1.0));
    assert_vec(c.d, CAMERA_CENTRE.d.into(), 1e-6);
    assert_vec(c.o, CAMERA_CENTRE.o.into(), 1e-6);
    assert_vec(s.camera.ray(Vec2::new(4.0, 2.0)).d, CAMERA_OPPOSITE_CORNER.d.into(), 1e-6);
    assert_eq!((s.film.width(), s.film.height()), (4, 2));
}

#[test]
fn default_focal_length_gives_38_1848_degrees_at_4_to_3() {
    // §4: no fov → focal_length "50mm" → x_fov 38.1848° at 4:3 [verified]; the default film
    // is 768×576 (§6), which is 4:3 (Mitsuba's: `DEFAULT_FILM_SIZE`, `DEFAULT_X_FOV`).
    let s = ok(&scene("<sensor type=\"perspective\"/>"));
    assert_eq!((s.film.width(), s.film.height()), DEFAULT_FILM_SIZE);
    assert!((tan_half_x_fov(&s) - tan_half_deg(DEFAULT_X_FOV)).abs() < 2e-6);
    // An explicit 35 mm lens: diagonal half-angle tan = √(36²+24²)/(2·35) on the 36×24 frame,
    // horizontal = diagonal / √(1 + 1/a²) (§4, `diagonal`).
    let s = camera("<string name=\"focal_length\" value=\"35mm\"/>", 768, 576);
    let want = ((36.0f64 * 36.0 + 24.0 * 24.0).sqrt() / 70.0 / (1.0f64 + 9.0 / 16.0).sqrt()) as f32;
    assert!((tan_half_x_fov(&s) - want).abs() < 2e-6, "{} vs {want}", tan_half_x_fov(&s));
    // "35" without the unit means the same (Mitsuba strips an optional "mm").
    let t = camera("<string name=\"focal_length\" value=\"35\"/>", 768, 576);
    assert_eq!(tan_half_x_fov(&t), tan_half_x_fov(&s));
}

#[test]
fn fov_axis_converts_with_the_full_film_aspect() {
    // §4 [verified]: fov 45 at 768×576 → y 57.8224, diagonal 36.6674, smaller 57.8224, larger 45
    // (Mitsuba's: `FOV_45_X_FOV`).
    for &(axis, x_fov) in FOV_45_X_FOV {
        let s = camera(
            &format!("<float name=\"fov\" value=\"45\"/><string name=\"fov_axis\" value=\"{axis}\"/>"),
            768,
            576,
        );
        assert!((tan_half_x_fov(&s) - tan_half_deg(x_fov)).abs() < 2e-6, "{axis}");
    }
    // Portrait film (a < 1): smaller is x, larger is y: tan = tan(fov/2)·a for larger, tan(fov/2)
    // for smaller (Mitsuba's: `FOV_45_PORTRAIT_TAN_HALF`).
    for &(axis, tan_half) in FOV_45_PORTRAIT_TAN_HALF {
        let s = camera(
            &format!("<float name=\"fov\" value=\"45\"/><string name=\"fov_axis\" value=\"{axis}\"/>"),
            576,
            768,
        );
        assert!((tan_half_x_fov(&s) - tan_half).abs() < 2e-6, "{axis}");
    }
}

/// Mitsuba's rays: `NEAR_FAR_CENTRE`, `NEAR_FAR_CORNER`, `PRINCIPAL_POINT_CENTRE`,
/// `PLAIN_AT_SHIFTED_CENTRE`, `TURNED_CAMERA_CENTRE`.
#[test]
fn near_far_clip_principal_point_and_to_world() {
    let s = camera(
        "<float name=\"fov\" value=\"90\"/><float name=\"near_clip\" value=\"0.5\"/><float name=\"far_clip\" value=\"20\"/>",
        4,
        2,
    );
    // The centre ray starts at (0, 0, 0.5) and is 19.5 long; a corner ray (d_local.z = 2/3 as in
    // the verified example) starts at d·0.75 and is 19.5·1.5 long.
    let r = s.camera.ray(Vec2::new(2.0, 1.0));
    assert_vec(r.o, NEAR_FAR_CENTRE.o.into(), 1e-6);
    assert!((r.maxt - NEAR_FAR_CENTRE.maxt).abs() < 1e-5);
    let r = s.camera.ray(Vec2::ZERO);
    assert_vec(r.o, NEAR_FAR_CORNER.o.into(), 1e-6);
    assert!((r.maxt - NEAR_FAR_CORNER.maxt).abs() < 1e-4);

    // Principal point offsets are fractions of the film added to the screen position (§4).
    let off = camera(
        "<float name=\"fov\" value=\"60\"/><float name=\"principal_point_offset_x\" value=\"0.25\"/>\
                      <float name=\"principal_point_offset_y\" value=\"-0.125\"/>",
        8,
        4,
    );
    let plain = camera("<float name=\"fov\" value=\"60\"/>", 8, 4);
    let (off_centre, plain_shifted) = (off.camera.ray(Vec2::new(4.0, 2.0)).d, plain.camera.ray(Vec2::new(6.0, 1.5)).d);
    assert_vec(off_centre, plain_shifted, 1e-6);
    assert_vec(off_centre, PRINCIPAL_POINT_CENTRE.d.into(), 1e-6);
    assert_vec(plain_shifted, PLAIN_AT_SHIFTED_CENTRE.d.into(), 1e-6);

    // to_world: a translated, turned camera (rotate +90° about y takes local +z to world +x).
    let s = camera(
        "<float name=\"fov\" value=\"90\"/><transform name=\"to_world\"><rotate y=\"1\" angle=\"90\"/><translate x=\"1\" y=\"2\" z=\"3\"/></transform>",
        4,
        2,
    );
    let r = s.camera.ray(Vec2::new(2.0, 1.0));
    assert_vec(r.d, TURNED_CAMERA_CENTRE.d.into(), 1e-6);
    assert_vec(r.o, TURNED_CAMERA_CENTRE.o.into(), 1e-6);
}

#[test]
fn camera_transform_may_mirror_but_not_scale_or_shear() {
    // Mitsuba's test is `has_scale`: the rows of the linear part orthonormal to 1e-3. A mirror
    // passes and simply mirrors the rays: d_world = M·d_local with M = lookat·S(−1, 1, 1).
    let s = camera(
        "<float name=\"fov\" value=\"90\"/><transform name=\"to_world\"><scale x=\"-1\"/>\
         <lookat origin=\"0,0,5\" target=\"0,0,0\" up=\"0,1,0\"/></transform>",
        4,
        2,
    );
    assert_vec(s.camera.ray(Vec2::ZERO).d, Vec3::new(2.0, 1.0, -2.0) / 3.0, 1e-6);
    // 1.0004² − 1 < 1e-3: accepted (as by Mitsuba); 1.0008² − 1 > 1e-3: rejected.
    camera("<transform name=\"to_world\"><scale value=\"1.0004\"/></transform>", 4, 2);
    let sensor = |tf: &str| {
        scene(&format!("<sensor type=\"perspective\">\n<transform name=\"to_world\">{tf}</transform>\n</sensor>"))
    };
    assert_err(load(&sensor("<scale value=\"2\"/>")), 3, "scale factors are not allowed");
    assert_err(load(&sensor("<scale value=\"1.0008\"/>")), 3, "scale factors are not allowed");
    // Unit-length but not orthogonal columns: a shear.
    assert_err(load(&sensor("<matrix value=\"1 0.5 0 0  0 0.8660254 0 0  0 0 1 0  0 0 0 1\"/>")), 3, "not allowed");
}

/// `src/sensors/orthographic.cpp` + `orthographic_projection` (`include/mitsuba/render/
/// sensor.h`): camera-space x ∈ [−1, 1] maps to image columns right-to-left, y ∈ [−1/aspect,
/// 1/aspect] to rows bottom-to-top; the ray starts at z = near_clip and runs far − near.
#[test]
fn orthographic_camera_rays() {
    let xml = scene(
        r#"<sensor type="orthographic">
<float name="near_clip" value="0.5"/><float name="far_clip" value="20"/>
<transform name="to_world"><scale value="2"/><translate value="1, 2, 3"/></transform>
<film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="2"/></film></sensor>"#,
    );
    let s = load(&xml).unwrap();
    // aspect 2: pixel corner (0, 0) is camera (1, 0.5, 0.5) → world 2·p + (1, 2, 3).
    let cases = [
        (Vec2::ZERO, Vec3::new(3.0, 3.0, 4.0)),
        (Vec2::new(4.0, 2.0), Vec3::new(-1.0, 1.0, 4.0)),
        (Vec2::new(2.0, 1.0), Vec3::new(1.0, 2.0, 4.0)),
    ];
    for (pos, o) in cases {
        let r = s.camera.ray(pos);
        assert!((r.o - o).length() < 1e-5, "{pos}: o = {}, expected {o}", r.o);
        assert!((r.d - Vec3::Z).length() < 1e-6, "d = {}", r.d);
        assert!((r.maxt - 19.5).abs() < 1e-5, "maxt = {}", r.maxt);
    }
    let bad = scene("<sensor type=\"orthographic\">\n<float name=\"far_clip\" value=\"0.001\"/></sensor>");
    assert_err_at(load(&bad), Path::new(FILE), 2, "far_clip");
    let fov = scene("<sensor type=\"orthographic\">\n<float name=\"fov\" value=\"30\"/></sensor>");
    assert_err_at(load(&fov), Path::new(FILE), 3, "fov");
}

#[test]
fn film_defaults_size_crop_and_filters() {
    // §6: 768×576, Gaussian σ 0.5, no crop.
    for xml in ["<sensor type=\"perspective\"/>", "<sensor type=\"perspective\"><film type=\"hdrfilm\"/></sensor>"] {
        let s = ok(&scene(xml));
        assert_eq!((s.film.width(), s.film.height()), (768, 576));
        assert_eq!(s.film.crop(), CropWindow { offset: [0, 0], size: [768, 576] });
        assert_eq!(s.film.filter(), ReconstructionFilter::Gaussian { stddev: 0.5 });
    }
    let film = |inner: &str| {
        ok(&scene(&format!(
            "<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/>\
             <integer name=\"height\" value=\"6\"/>{inner}</film></sensor>"
        )))
    };
    let s = film(
        "<integer name=\"crop_offset_x\" value=\"2\"/><integer name=\"crop_offset_y\" value=\"1\"/>\
                  <integer name=\"crop_width\" value=\"4\"/><integer name=\"crop_height\" value=\"3\"/>",
    );
    assert_eq!((s.film.width(), s.film.height()), (8, 6));
    assert_eq!(s.film.crop(), CropWindow { offset: [2, 1], size: [4, 3] });
    // The camera still projects the full film (§6 crop): same rays as without the crop.
    let full = film("");
    for p in [Vec2::ZERO, Vec2::new(2.5, 1.5), Vec2::new(8.0, 6.0)] {
        assert_eq!(s.camera.ray(p).d, full.camera.ray(p).d);
    }
    // A size alone keeps offset 0.
    assert_eq!(
        film("<integer name=\"crop_width\" value=\"5\"/>").film.crop(),
        CropWindow { offset: [0, 0], size: [5, 6] }
    );
    // Filters with their defaults: box; tent radius 1; gaussian σ 0.5.
    let filter = |xml: &str| film(xml).film.filter();
    assert_eq!(filter("<rfilter type=\"box\"/>"), ReconstructionFilter::Box);
    assert_eq!(filter("<rfilter type=\"tent\"/>"), ReconstructionFilter::Tent { radius: 1.0 });
    assert_eq!(
        filter("<rfilter type=\"tent\"><float name=\"radius\" value=\"1.5\"/></rfilter>"),
        ReconstructionFilter::Tent { radius: 1.5 }
    );
    assert_eq!(filter("<rfilter type=\"gaussian\"/>"), ReconstructionFilter::Gaussian { stddev: 0.5 });
    assert_eq!(
        filter("<rfilter type=\"gaussian\"><float name=\"stddev\" value=\"0.25\"/></rfilter>"),
        ReconstructionFilter::Gaussian { stddev: 0.25 }
    );
    // Output-format properties are read (they only matter for files Mitsuba writes).
    film(
        "<string name=\"pixel_format\" value=\"RGBA\"/><string name=\"component_format\" value=\"float32\"/><string name=\"file_format\" value=\"openexr\"/>",
    );
}

#[test]
fn sampler_defaults_and_values() {
    // §5: sample_count 4, seed 0.
    let s = ok(&with_sensor(""));
    assert_eq!((s.sampling.spp, s.sampling.seed), (4, 0));
    let s = ok(&scene(
        "<sensor type=\"perspective\"><sampler type=\"independent\"><integer name=\"sample_count\" value=\"16\"/>\
         <integer name=\"seed\" value=\"7\"/></sampler></sensor>",
    ));
    assert_eq!((s.sampling.spp, s.sampling.seed), (16, 7));
}

#[test]
fn sensor_film_sampler_errors() {
    let sensor = |inner: &str| scene(&format!("<sensor type=\"perspective\">\n{inner}\n</sensor>"));
    assert_err(load(&scene("<sensor type=\"radiancemeter\"/>")), 2, "unsupported sensor type \"radiancemeter\"");
    assert_err(load(&scene("<sensor type=\"thinlens\"/>")), 2, "needs the property \"aperture_radius\"");
    assert_err(
        load(&sensor("<float name=\"fov\" value=\"45\"/>\n<string name=\"focal_length\" value=\"35mm\"/>")),
        2,
        "either fov or focal_length",
    );
    assert_err(
        load(&sensor("<float name=\"fov\" value=\"45\"/>\n<string name=\"fov_axis\" value=\"z\"/>")),
        4,
        "fov_axis",
    );
    assert_err(load(&sensor("<string name=\"fov_axis\" value=\"y\"/>")), 3, "unreferenced property \"fov_axis\"");
    assert_err(load(&sensor("<float name=\"fov\" value=\"180\"/>")), 3, "fov");
    assert_err(load(&sensor("<float name=\"fov\" value=\"0\"/>")), 3, "fov");
    assert_err(load(&sensor("<string name=\"fov\" value=\"45\"/>")), 3, "wrong type");
    assert_err(load(&sensor("<string name=\"focal_length\" value=\"wide\"/>")), 3, "focal_length");
    assert_err(load(&sensor("<string name=\"focal_length\" value=\"0mm\"/>")), 3, "focal_length");
    assert_err(load(&sensor("<float name=\"near_clip\" value=\"0\"/>")), 3, "near_clip");
    // A principal point offset that is NaN or would overflow the ray direction (matte's limit).
    assert_err(
        load(&sensor("<float name=\"principal_point_offset_y\" value=\"nan\"/>")),
        3,
        "principal_point_offset_y",
    );
    assert_err(
        load(&sensor("<float name=\"principal_point_offset_x\" value=\"1e30\"/>")),
        3,
        "principal_point_offset_x",
    );
    assert_err(
        load(&sensor("<float name=\"near_clip\" value=\"5\"/>\n<float name=\"far_clip\" value=\"2\"/>")),
        2,
        "far_clip",
    );
    assert_err(load(&sensor("<shape type=\"sphere\"/>")), 3, "cannot be nested in a sensor");
    assert_err(load(&sensor("<film type=\"hdrfilm\"/>\n<film type=\"hdrfilm\"/>")), 4, "only one film");
    assert_err(
        load(&sensor("<sampler type=\"independent\"/>\n<sampler type=\"independent\"/>")),
        4,
        "only one sampler",
    );
    // Film.
    assert_err(load(&sensor("<film type=\"specfilm\"/>")), 3, "unsupported film type \"specfilm\"");
    let film = |inner: &str| {
        sensor(&format!("<film type=\"hdrfilm\">\n<integer name=\"width\" value=\"8\"/>\n{inner}\n</film>"))
    };
    assert_err(load(&film("<integer name=\"height\" value=\"0\"/>")), 5, "height");
    assert_err(load(&film("<float name=\"height\" value=\"6\"/>")), 5, "wrong type");
    // An offset alone keeps the full-size default crop, which then sticks out (Mitsuba:
    // "Invalid crop window specification").
    assert_err(load(&film("<integer name=\"crop_offset_x\" value=\"2\"/>")), 3, "invalid crop window");
    assert_err(
        load(&film("<integer name=\"crop_offset_x\" value=\"4\"/>\n<integer name=\"crop_width\" value=\"5\"/>")),
        3,
        "invalid crop window",
    );
    assert_err(load(&film("<integer name=\"crop_width\" value=\"0\"/>")), 5, "crop_width");
    assert_err(load(&film("<string name=\"pixel_format\" value=\"xyz\"/>")), 5, "pixel_format");
    assert_err(load(&film("<boolean name=\"sample_border\" value=\"true\"/>")), 5, "sample_border");
    assert_err(load(&film("<rfilter type=\"sinc\"/>")), 5, "unsupported rfilter type \"sinc\"");
    assert_err(load(&film("<rfilter type=\"tent\">\n<float name=\"radius\" value=\"-1\"/>\n</rfilter>")), 6, "radius");
    assert_err(
        load(&film("<rfilter type=\"gaussian\">\n<float name=\"sigma\" value=\"1\"/>\n</rfilter>")),
        6,
        "unreferenced property \"sigma\"",
    );
    // Filters wider than 1024 px (4σ for the Gaussian) cannot get their image-block border.
    assert_err(
        load(&film("<rfilter type=\"tent\">\n<float name=\"radius\" value=\"2000\"/>\n</rfilter>")),
        6,
        "filter radius",
    );
    assert_err(
        load(&film("<rfilter type=\"gaussian\">\n<float name=\"stddev\" value=\"300\"/>\n</rfilter>")),
        6,
        "filter radius",
    );
    assert_err(
        load(&film("<rfilter type=\"box\"/>\n<rfilter type=\"tent\"/>")),
        6,
        "only have one reconstruction filter",
    );
    assert_err(load(&film("<sampler type=\"independent\"/>")), 5, "cannot be nested in a film");
    // Sampler.
    assert_err(load(&sensor("<sampler type=\"sobol\"/>")), 3, "unsupported sampler type \"sobol\"");
    assert_err(
        load(&sensor("<sampler type=\"orthogonal\">\n<integer name=\"strength\" value=\"0\"/>\n</sampler>")),
        4,
        "strength",
    );
    let sampler = |inner: &str| sensor(&format!("<sampler type=\"independent\">\n{inner}\n</sampler>"));
    assert_err(load(&sampler("<integer name=\"sample_count\" value=\"0\"/>")), 4, "sample_count");
    assert_err(load(&sampler("<float name=\"sample_count\" value=\"4\"/>")), 4, "wrong type");
    assert_err(load(&sampler("<integer name=\"seed\" value=\"-1\"/>")), 4, "seed");
    // Scene level.
    // Several sensors: each is built (a bad one is an error), the first in document order is
    // rendered (Mitsuba's `mi.render(scene)`), and a note says so.
    let wide = SENSOR
        .replace("<sensor type=\"perspective\">", "<sensor type=\"perspective\"><float name=\"fov\" value=\"80\"/>");
    assert_ne!(wide, SENSOR, "the replacement must apply");
    let two = ok(&scene(&format!("{SENSOR}\n{wide}")));
    assert_eq!(two.notes.len(), 1, "{:?}", two.notes);
    assert!(two.notes[0].contains("more than one <sensor>") && two.notes[0].contains(":3:"), "{:?}", two.notes);
    let first_fov = tan_half_x_fov(&ok(&scene(SENSOR)));
    assert!((tan_half_x_fov(&two) - first_fov).abs() < 1e-6, "the first sensor is rendered");
    assert!((tan_half_x_fov(&ok(&scene(&format!("{wide}\n{SENSOR}")))) - tan_half_deg(80.0)).abs() < 1e-5);
    let bad = SENSOR
        .replace("<sensor type=\"perspective\">", "<sensor type=\"perspective\"><float name=\"fvo\" value=\"80\"/>");
    assert_err(load(&scene(&format!("{SENSOR}\n{bad}"))), 3, "unreferenced property \"fvo\"");
    assert_err(load(&scene("<shape type=\"sphere\"/>")), 1, "no <sensor>");
}
