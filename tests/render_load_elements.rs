//! Loader tests for the Mitsuba elements added for Mitsuba's own test scenes (docs/validation.md, "Mitsuba's own render tests"):
//! `<path>`, integrator `moment`, sensor `orthographic`, texture `checkerboard`. Expected
//! values are Mitsuba 3.9.1's documented semantics (the source file is named at each test)
//! worked out by hand; errors name `file:line`.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};
use matte::render::bsdf::Bsdf;
use matte::render::emitter::Emitter;
use matte::render::geometry::Ray;
use matte::render::integrator::Integrator;
use matte::render::load::{LoadedScene, load_file, load_str};
use matte::scene_file::SceneError;

const FILE: &str = "/virtual/scenes/scene.xml";
const SENSOR: &str = r#"<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="2"/></film></sensor>"#;

fn load(xml: &str) -> Result<LoadedScene, SceneError> {
    load_str(xml, Path::new(FILE), &[])
}

fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>")
}

fn assert_err_at<T>(r: Result<T, SceneError>, file: &Path, line: u32, needle: &str) {
    let Err(e) = r else { panic!("expected an error containing {needle:?}") };
    let text = e.to_string();
    assert!(!text.contains('\n'), "multi-line error: {text}");
    assert!(text.starts_with(&format!("{}:{line}:", file.display())), "expected {}:{line} in: {text}", file.display());
    assert!(text.contains(needle), "expected {needle:?} in: {text}");
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("matte_elements_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const TRIANGLE_OBJ: &str = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";

/// `src/core/parser.cpp` (`TagType::Resource`): a relative `<path>` is taken from the XML
/// file's folder; assets are then found there before the scene's own folder.
#[test]
fn path_adds_a_search_folder() {
    let dir = temp_dir("path");
    std::fs::create_dir_all(dir.join("assets/meshes")).unwrap();
    std::fs::create_dir_all(dir.join("scenes")).unwrap();
    std::fs::write(dir.join("assets/meshes/tri.obj"), TRIANGLE_OBJ).unwrap();
    let body = |path: &str| {
        scene(&format!(
            "{path}\n{SENSOR}\n<shape type=\"obj\"><string name=\"filename\" value=\"meshes/tri.obj\"/></shape>"
        ))
    };
    let file = dir.join("scenes/s.xml");
    std::fs::write(&file, body("<path value=\"../assets\"/>")).unwrap();
    let s = load_file(&file, &[]).expect("the mesh is found through <path>");
    let si = s.scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, f32::INFINITY)).expect("triangle hit");
    assert!((si.t - 1.0).abs() < 1e-6);
    // Without the <path>, the file is looked for next to the scene and is missing (line 4).
    std::fs::write(&file, body("")).unwrap();
    assert_err_at(load_file(&file, &[]), &file, 4, "tri.obj");
    // A folder that does not exist, and a <path> below the root, are errors at their line.
    std::fs::write(&file, body("<path value=\"../nowhere\"/>")).unwrap();
    assert_err_at(load_file(&file, &[]), &file, 2, "<path>: folder");
    let nested = scene(&format!("{SENSOR}\n<shape type=\"obj\">\n<path value=\"../assets\"/>\n</shape>"));
    std::fs::write(&file, nested).unwrap();
    assert_err_at(load_file(&file, &[]), &file, 4, "<path> can only be a child of the root");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Mitsuba's `<include>` and `<path>` in nested files (`src/core/parser.cpp`,
/// `TagType::Include` and `TagType::Resource`, checked against Mitsuba 3.9.1's `load_file` on
/// this layout): an include's `<path>` that is missing next to it is resolved through the
/// resolver, whose first folder is the including file's; a nested `<include>` is found through
/// that `<path>`; but a `<path>` in an included file lasts only while that file is parsed, so
/// it does not find the scene's assets.
#[test]
fn nested_includes_resolve_paths_like_mitsuba() {
    let dir = temp_dir("nested_paths");
    for d in ["x/y/include", "common", "meshes"] {
        std::fs::create_dir_all(dir.join(d)).unwrap();
    }
    std::fs::write(dir.join("meshes/tri.obj"), TRIANGLE_OBJ).unwrap();
    let main = |mesh: &str| {
        scene(&format!(
            "{SENSOR}\n<include filename=\"include/inc.xml\"/>\n\
             <shape type=\"obj\"><string name=\"filename\" value=\"{mesh}\"/><ref id=\"m\"/></shape>"
        ))
    };
    // `../../common` is not next to include/inc.xml (x/common); it is found from x/y/.
    let inc = "<scene version=\"3.0.0\">\n<path value=\"../../common\"/>\n<include filename=\"mat.xml\"/>\n</scene>";
    std::fs::write(dir.join("x/y/include/inc.xml"), inc).unwrap();
    let mat = "<scene version=\"3.0.0\">\n<path value=\"../meshes\"/>\n<bsdf type=\"diffuse\" id=\"m\"/>\n</scene>";
    std::fs::write(dir.join("common/mat.xml"), mat).unwrap();
    let file = dir.join("x/y/main.xml");
    std::fs::write(&file, main("../../meshes/tri.obj")).unwrap();
    let s = load_file(&file, &[]).expect("the includes and the mesh resolve as in Mitsuba");
    assert!(s.scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, f32::INFINITY)).is_some());
    // mat.xml's `<path value="../meshes"/>` does not outlive mat.xml: Mitsuba reports
    // `OBJ file "tri.obj": file not found` here.
    std::fs::write(&file, main("tri.obj")).unwrap();
    assert_err_at(load_file(&file, &[]), &file, 4, "tri.obj");
    // An include that is nowhere: the error names the file the resolver fell back to.
    std::fs::write(dir.join("x/y/include/inc.xml"), inc.replace("mat.xml", "nothing.xml")).unwrap();
    assert_err_at(load_file(&file, &[]), &dir.join("x/y/include/inc.xml"), 3, "nothing.xml");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `src/integrators/moment.cpp`: the image is the first nested integrator's.
#[test]
fn moment_renders_its_nested_integrator() {
    let s = load(&scene(&format!("{SENSOR}\n<integrator type=\"moment\"><integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"3\"/></integrator></integrator>"))).unwrap();
    match s.integrator {
        Integrator::Direct(d) => assert_eq!(d.emitter_samples, 3),
        other => panic!("expected the nested direct integrator, got {other:?}"),
    }
    let s = load(&scene(&format!("{SENSOR}\n<integrator type=\"moment\"><integrator type=\"path\"><integer name=\"max_depth\" value=\"2\"/></integrator><integrator type=\"direct\"/></integrator>"))).unwrap();
    assert!(matches!(s.integrator, Integrator::Path(ref p) if p.max_depth == 2), "{:?}", s.integrator);
    assert_err_at(
        load(&scene(&format!("{SENSOR}\n<integrator type=\"moment\"/>"))),
        Path::new(FILE),
        3,
        "needs at least one nested <integrator>",
    );
    assert_err_at(
        load(&scene(&format!("{SENSOR}\n<integrator type=\"moment\">\n<integrator type=\"bogus\"/></integrator>"))),
        Path::new(FILE),
        4,
        "unsupported integrator type \"bogus\"",
    );
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

/// `src/textures/checkerboard.cpp`: color0 where frac(u') and frac(v') are both > 1/2 or both
/// ≤ 1/2, color1 otherwise (uv' = to_uv·uv); defaults 0.4 and 0.2.
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
    let c0 = Vec3::splat(0.9);
    let c1 = Vec3::new(0.1, 0.2, 0.3);
    for (x, y, expect) in [
        (-0.75, -0.75, c0),
        (-0.25, -0.75, c1),
        (-0.25, -0.25, c0),
        (0.25, -0.75, c0),
        (0.75, -0.25, c0),
        (0.75, -0.75, c1),
        (0.75, 0.75, c0),
    ] {
        let got = reflectance_at(&s, x, y);
        assert!((got - expect).length() < 1e-6, "({x}, {y}): {got}, expected {expect}");
    }
    let d = load(&xml(r#"<texture type="checkerboard" name="reflectance"/>"#)).unwrap();
    assert!((reflectance_at(&d, -0.75, -0.75) - Vec3::splat(0.4)).length() < 1e-6);
    assert!((reflectance_at(&d, 0.25, -0.75) - Vec3::splat(0.2)).length() < 1e-6);
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
/// color0 = (0.9, 0.1, 0.2), color1 = 0.3.)
#[test]
fn checkerboard_eval_1_swaps_the_colours() {
    let xml = scene(&format!(
        "{SENSOR}\n<shape type=\"rectangle\"><bsdf type=\"mask\"><texture type=\"checkerboard\" name=\"opacity\"><rgb name=\"color0\" value=\"0.9, 0.1, 0.2\"/><float name=\"color1\" value=\"0.3\"/></texture><bsdf type=\"diffuse\"/></bsdf></shape>"
    ));
    let s = load(&xml).unwrap();
    let si = s.scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, f32::INFINITY)).expect("hit");
    let Bsdf::Mask(m) = s.scene.bsdf(&si) else { panic!("expected a mask") };
    let c0_mean = (0.9 + 0.1 + 0.2) / 3.0;
    for (uv, eval, eval_1) in [
        (Vec2::new(0.25, 0.25), Vec3::new(0.9, 0.1, 0.2), 0.3),
        (Vec2::new(0.75, 0.25), Vec3::splat(0.3), c0_mean),
        (Vec2::new(0.75, 0.75), Vec3::new(0.9, 0.1, 0.2), 0.3),
        (Vec2::new(1.25, 0.75), Vec3::splat(0.3), c0_mean),
    ] {
        assert!((m.opacity.eval(uv) - eval).length() < 1e-6, "eval at {uv}");
        assert!((m.opacity.eval_1(uv) - eval_1).abs() < 1e-6, "eval_1 at {uv}: {}", m.opacity.eval_1(uv));
    }
    assert!((m.opacity.mean() - 0.5 * (c0_mean + 0.3)).abs() < 1e-6);
}

/// `src/bsdfs/mask.cpp`: `opacity` defaults to 0.5 (a float or a texture), exactly one nested
/// BSDF; a `twosided` around a mask is an error (its null component is a transmission,
/// `src/bsdfs/twosided.cpp`); unknown properties are errors.
#[test]
fn mask_defaults_and_errors() {
    let xml = |bsdf: &str| scene(&format!("{SENSOR}\n<shape type=\"rectangle\">\n{bsdf}\n</shape>"));
    let s = load(&xml(r#"<bsdf type="mask"><bsdf type="diffuse"/></bsdf>"#)).unwrap();
    let si = s.scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, f32::INFINITY)).expect("hit");
    let Bsdf::Mask(m) = s.scene.bsdf(&si) else { panic!("expected a mask") };
    assert_eq!(m.opacity(&si), 0.5);
    assert!(matches!(*m.nested, Bsdf::Diffuse { .. }));
    let clipped = load(&xml(r#"<bsdf type="mask"><float name="opacity" value="0.25"/><bsdf type="diffuse"/></bsdf>"#));
    let Bsdf::Mask(m) = clipped.as_ref().unwrap().scene.bsdf(&si) else { panic!() };
    assert_eq!(m.opacity(&si), 0.25);
    assert_err_at(load(&xml("<bsdf type=\"mask\"/>")), Path::new(FILE), 4, "found 0");
    assert_err_at(
        load(&xml("<bsdf type=\"mask\"><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf>")),
        Path::new(FILE),
        4,
        "found 2",
    );
    assert_err_at(
        load(&xml("<bsdf type=\"twosided\"><bsdf type=\"mask\"><bsdf type=\"diffuse\"/></bsdf></bsdf>")),
        Path::new(FILE),
        4,
        "allow_transmission",
    );
    assert_err_at(
        load(&xml("<bsdf type=\"mask\"><float name=\"opacty\" value=\"0.5\"/><bsdf type=\"diffuse\"/></bsdf>")),
        Path::new(FILE),
        4,
        "opacty",
    );
}

/// `src/bsdfs/blendbsdf.cpp`: exactly two nested BSDFs and a `weight` (no default);
/// `src/bsdfs/bumpmap.cpp`: one nested BSDF and one texture child of any name, `scale` 1,
/// `flip_invalid_normals` and `use_shadowing_function` true. matte needs a bitmap height map
/// (Mitsuba's other textures have no gradient) and a mesh (its analytic shapes have no
/// ∂p/∂u, ∂p/∂v).
#[test]
fn blendbsdf_and_bumpmap_defaults_and_errors() {
    let xml = |shape: &str, bsdf: &str| scene(&format!("{SENSOR}\n<shape type=\"{shape}\">\n{bsdf}\n</shape>"));
    let blend = load(&xml(
        "rectangle",
        r#"<bsdf type="blendbsdf"><float name="weight" value="0.3"/><bsdf type="diffuse"/><bsdf type="conductor"/></bsdf>"#,
    ))
    .unwrap();
    let si = blend.scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, f32::INFINITY)).expect("hit");
    let Bsdf::Blend(b) = blend.scene.bsdf(&si) else { panic!("expected a blend") };
    assert!((b.weight(&si) - 0.3).abs() < 1e-7);
    assert!(matches!((&*b.first, &*b.second), (Bsdf::Diffuse { .. }, Bsdf::Conductor(_))));
    let no_weight =
        xml("rectangle", "<bsdf type=\"blendbsdf\"><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf>");
    assert_err_at(load(&no_weight), Path::new(FILE), 4, "weight");
    let one = xml(
        "rectangle",
        "<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.5\"/><bsdf type=\"diffuse\"/></bsdf>",
    );
    assert_err_at(load(&one), Path::new(FILE), 4, "found 1");

    let dir = temp_dir("bumpmap");
    let height = dir.join("h.exr");
    write_exr(&height, 4, 4, |i, j| Vec3::splat((i + 2 * j) as f32 / 10.0));
    let bump =
        |shape: &str, tex: &str| xml(shape, &format!("<bsdf type=\"bumpmap\">{tex}<bsdf type=\"diffuse\"/></bsdf>",));
    let bitmap = format!(
        "<texture type=\"bitmap\" name=\"any_name\"><string name=\"filename\" value=\"{}\"/></texture>",
        height.display()
    );
    let s = load(&bump("rectangle", &bitmap)).unwrap();
    let Bsdf::BumpMap(m) = s.scene.bsdf(&si) else { panic!("expected a bumpmap") };
    assert_eq!((m.scale, m.flip_invalid_normals, m.use_shadowing_function), (1.0, true, true));
    assert_err_at(load(&bump("sphere", &bitmap)), Path::new(FILE), 4, "meshes only");
    assert_err_at(
        load(&bump("rectangle", "<texture type=\"checkerboard\" name=\"h\"/>")),
        Path::new(FILE),
        4,
        "bitmap height texture",
    );
    assert_err_at(load(&bump("rectangle", "")), Path::new(FILE), 4, "found 0");
}

/// `src/emitters/area.cpp`: `radiance` may be a texture, looked up at the hit's uv (here a
/// 2×2 EXR on a rectangle, uv = ((x+1)/2, (y+1)/2), nearest lookup); a mesh attribute as
/// radiance is refused by matte.
#[test]
fn area_emitter_radiance_texture() {
    let dir = temp_dir("area_texture");
    let tex = dir.join("r.exr");
    write_exr(&tex, 2, 2, |i, j| Vec3::new(1.0 + i as f32, 3.0 + j as f32, 0.5));
    let xml = scene(&format!(
        "{SENSOR}\n<shape type=\"rectangle\"><emitter type=\"area\"><texture type=\"bitmap\" name=\"radiance\"><string name=\"filename\" value=\"{}\"/><string name=\"filter_type\" value=\"nearest\"/></texture></emitter></shape>",
        tex.display()
    ));
    let s = load(&xml).unwrap();
    for (x, y, want) in [
        (-0.5, -0.5, Vec3::new(1.0, 3.0, 0.5)),
        (0.5, -0.5, Vec3::new(2.0, 3.0, 0.5)),
        (0.5, 0.5, Vec3::new(2.0, 4.0, 0.5)),
    ] {
        let si = s.scene.intersect(&Ray::new(Vec3::new(x, y, 1.0), Vec3::NEG_Z, f32::INFINITY)).expect("hit");
        let got = s.scene.emitters[0].eval_surface(&si);
        assert!((got - want).abs().max_element() < 1e-6, "({x}, {y}): {got} vs {want}");
    }
    let attr = scene(&format!(
        "{SENSOR}\n<shape type=\"rectangle\"><emitter type=\"area\">\n<texture type=\"mesh_attribute\" name=\"radiance\"><string name=\"name\" value=\"vertex_color\"/></texture></emitter></shape>"
    ));
    assert!(load(&attr).is_err());
}

/// Writes a W×H EXR whose texel (i, j) is `f(i, j)`.
fn write_exr(path: &Path, w: u32, h: u32, f: impl Fn(u32, u32) -> Vec3) {
    let mut img = matte::render::film::Image::new(w, h);
    for j in 0..h {
        for i in 0..w {
            img.set(i, j, f(i, j));
        }
    }
    matte::render::image_io::write_exr(path, &img).unwrap();
}

fn first_emitter(s: &LoadedScene) -> &Emitter {
    &s.scene.emitters[0]
}

/// `src/emitters/spot.cpp`: the texture multiplies the intensity at uv = ½ + ½·(x, y)/(z·tan
/// cutoff) of the local direction; the falloff is unchanged.
#[test]
fn spot_texture_is_looked_up_along_the_local_direction() {
    let dir = temp_dir("spot");
    // 2×2 texels: (0,0) red, (1,0) green, (0,1) blue, (1,1) white; nearest lookup.
    let colours = [Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE];
    write_exr(&dir.join("t.exr"), 2, 2, |i, j| colours[(j * 2 + i) as usize]);
    let file = dir.join("s.xml");
    std::fs::write(
        &file,
        scene(&format!(
            "{SENSOR}\n<emitter type=\"spot\"><rgb name=\"intensity\" value=\"2\"/><float name=\"cutoff_angle\" value=\"40\"/><float name=\"beam_width\" value=\"39\"/>\
             <texture name=\"texture\" type=\"bitmap\"><string name=\"filename\" value=\"t.exr\"/><string name=\"filter_type\" value=\"nearest\"/></texture></emitter>"
        )),
    )
    .unwrap();
    let s = load_file(&file, &[]).unwrap();
    let e = first_emitter(&s);
    let t = 40f32.to_radians().tan();
    // A point at depth 2 and lateral offset (a, b)·2: local direction ∝ (a, b, 1); uv = ½ + ½(a, b)/t.
    for (a, b, texel) in [(-0.3f32, -0.3f32, 0usize), (0.3, -0.3, 1), (-0.3, 0.3, 2), (0.3, 0.3, 3)] {
        let p = Vec3::new(2.0 * a, 2.0 * b, 2.0);
        let es = e.sample_direction(p, Vec2::ZERO, &s.scene.shapes).expect("inside the cone");
        let uv = Vec2::new(0.5 + 0.5 * a / t, 0.5 + 0.5 * b / t);
        assert!(uv.min_element() > 0.0 && uv.max_element() < 1.0);
        let expect = colours[texel] * 2.0 / p.length_squared();
        assert!(
            (es.weight - expect).length() < 1e-5 * expect.length().max(1.0),
            "({a}, {b}): {} vs {expect}",
            es.weight
        );
    }
    // A constant `texture` is refused, as in Mitsuba ("must be spatially varying").
    std::fs::write(
        &file,
        scene(&format!("{SENSOR}\n<emitter type=\"spot\">\n<rgb name=\"texture\" value=\"0.5\"/></emitter>")),
    )
    .unwrap();
    assert_err_at(load_file(&file, &[]), &file, 4, "spatially varying");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `src/emitters/projector.cpp`: a point at local (x, y, z) receives, along the direction to
/// the projector, π·scale·texture(uv) / (z²·cos θ), with uv the perspective projection (image
/// x towards local −x, y towards −y) at the texture's aspect ratio; nothing outside the image
/// or behind the projector.
#[test]
fn projector_casts_its_texture() {
    let dir = temp_dir("projector");
    let colours = [Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE];
    // 4×2 image: aspect 2; left half columns 0-1, right half 2-3; rows top/bottom.
    write_exr(&dir.join("t.exr"), 4, 2, |i, j| colours[(j * 2 + i / 2) as usize]);
    let file = dir.join("s.xml");
    std::fs::write(
        &file,
        scene(&format!(
            "{SENSOR}\n<emitter type=\"projector\"><float name=\"fov\" value=\"90\"/><float name=\"scale\" value=\"3\"/>\
             <texture name=\"irradiance\" type=\"bitmap\"><string name=\"filename\" value=\"t.exr\"/><string name=\"filter_type\" value=\"nearest\"/></texture></emitter>"
        )),
    )
    .unwrap();
    let s = load_file(&file, &[]).unwrap();
    let e = first_emitter(&s);
    // fov 90 along x: tan = 1; x ∈ [−z, z], y ∈ [−z/2, z/2]. Image column < 2 ↔ local x > 0.
    for (x, y, texel) in [(0.5f32, 0.25f32, 0usize), (-0.5, 0.25, 1), (0.5, -0.25, 2), (-0.5, -0.25, 3)] {
        let p = Vec3::new(x, y, 1.0);
        let es = e.sample_direction(p, Vec2::ZERO, &s.scene.shapes).expect("lit");
        let cos = 1.0 / p.length();
        let expect = colours[texel] * (std::f32::consts::PI * 3.0 / cos);
        assert!((es.weight - expect).length() < 1e-4 * expect.length(), "({x}, {y}): {} vs {expect}", es.weight);
        assert!(es.delta);
    }
    for p in [Vec3::new(1.5, 0.0, 1.0), Vec3::new(0.0, 0.7, 1.0), Vec3::new(0.0, 0.0, -1.0)] {
        assert!(e.sample_direction(p, Vec2::ZERO, &s.scene.shapes).is_none(), "{p} should be dark");
    }
    // A constant irradiance: aspect 1, π·scale/(z² cos θ).
    let c = load(&scene(&format!("{SENSOR}\n<emitter type=\"projector\"><float name=\"fov\" value=\"90\"/><rgb name=\"irradiance\" value=\"0.5\"/></emitter>"))).unwrap();
    let es = first_emitter(&c).sample_direction(Vec3::new(0.0, 0.9, 2.0), Vec2::ZERO, &c.scene.shapes).expect("lit");
    let cos = 2.0 / Vec3::new(0.0, 0.9, 2.0).length();
    assert!((es.weight - Vec3::splat(0.5 * std::f32::consts::PI / (4.0 * cos))).length() < 1e-5);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `envmap` through the loader: `scale` and `to_world` apply, the file is found through
/// `<path>`, and it is the scene's environment.
#[test]
fn envmap_loads_as_the_environment() {
    let dir = temp_dir("envmap");
    std::fs::create_dir_all(dir.join("tex")).unwrap();
    write_exr(&dir.join("tex/sky.exr"), 8, 5, |i, j| Vec3::new(0.1 * (i + 1) as f32, 0.2 * (j + 1) as f32, 0.5));
    let file = dir.join("s.xml");
    std::fs::write(
        &file,
        scene(&format!(
            "<path value=\"tex\"/>\n{SENSOR}\n<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/><float name=\"scale\" value=\"2\"/>\
             <transform name=\"to_world\"><rotate x=\"1\" angle=\"90\"/></transform></emitter>"
        )),
    )
    .unwrap();
    let s = load_file(&file, &[]).unwrap();
    let env = s.scene.environment.expect("an environment");
    // Row 2 (v = ½, the horizon), column 3 at u = 3.5/8: local d = (sin φ, 0, −cos φ);
    // rotating +90° about x maps local (x, y, z) to (x, −z, y).
    let phi = 2.0 * std::f32::consts::PI * 3.5 / 8.0;
    let local = Vec3::new(phi.sin(), 0.0, -phi.cos());
    let world = Vec3::new(local.x, -local.z, local.y);
    let got = s.scene.emitters[env as usize].eval_environment(world);
    assert!((got - 2.0 * Vec3::new(0.4, 0.6, 0.5)).length() < 1e-4, "{got}");
    std::fs::write(&file, scene(&format!("{SENSOR}\n<emitter type=\"constant\"/>\n<emitter type=\"envmap\"><string name=\"filename\" value=\"tex/sky.exr\"/></emitter>"))).unwrap();
    assert_err_at(load_file(&file, &[]), &file, 4, "only one environment emitter");
    std::fs::write(
        &file,
        scene(&format!("{SENSOR}\n<emitter type=\"envmap\"><string name=\"filename\" value=\"nope.exr\"/></emitter>")),
    )
    .unwrap();
    assert_err_at(load_file(&file, &[]), &file, 3, "nope.exr");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `shapegroup` / `instance` (`src/shapes/instance.cpp`): the group alone is not rendered;
/// each instance places every shape of it with instance·shape transforms.
#[test]
fn instances_place_their_group() {
    let group = r#"<shape type="shapegroup" id="g">
<shape type="sphere"><float name="radius" value="0.5"/></shape>
<shape type="rectangle"><transform name="to_world"><translate z="-1"/></transform></shape>
</shape>"#;
    let s = load(&scene(&format!(
        "{SENSOR}\n{group}\n<shape type=\"instance\"><ref id=\"g\"/></shape>\n<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\"><scale value=\"2\"/><translate x=\"10\"/></transform></shape>"
    )))
    .unwrap();
    assert_eq!(s.scene.shapes.len(), 4);
    let down = |x: f32| s.scene.intersect(&Ray::new(Vec3::new(x, 0.0, 5.0), Vec3::NEG_Z, f32::INFINITY)).map(|si| si.t);
    // Identity instance: sphere top at z = 0.5; scaled instance at x = 10: sphere radius 1.
    assert!((down(0.0).unwrap() - 4.5).abs() < 1e-4);
    assert!((down(10.0).unwrap() - 4.0).abs() < 1e-4);
    // Beside the spheres: the rectangles at z = −1 and z = −2 (scaled translate).
    assert!((down(0.75).unwrap() - 6.0).abs() < 1e-4);
    assert!((down(11.5).unwrap() - 7.0).abs() < 1e-4);
    assert!(down(5.0).is_none());
    // A group alone renders nothing.
    let alone = load(&scene(&format!("{SENSOR}\n{group}"))).unwrap();
    assert!(alone.scene.shapes.is_empty());
    // Errors: emitters in groups, nested groups, instances without a group.
    let bad_emitter = scene(&format!(
        "{SENSOR}\n<shape type=\"shapegroup\" id=\"g\"><shape type=\"sphere\">\n<emitter type=\"area\"/></shape></shape>\n<shape type=\"instance\"><ref id=\"g\"/></shape>"
    ));
    assert_err_at(load(&bad_emitter), Path::new(FILE), 4, "shapegroup");
    let nested =
        scene(&format!("{SENSOR}\n<shape type=\"shapegroup\" id=\"g\">\n<shape type=\"shapegroup\"/></shape>"));
    assert_err_at(load(&nested), Path::new(FILE), 4, "nested instancing");
    assert_err_at(
        load(&scene(&format!("{SENSOR}\n<shape type=\"instance\"/>"))),
        Path::new(FILE),
        3,
        "needs a shapegroup",
    );
}

/// The bundled scenes for these elements load, render without NaN, and the sun scene's
/// sphere shadows the ground straight below it (the straight-down sun regression).
#[test]
fn bundled_element_scenes_render() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("mitsuba_scenes");
    for name in ["sun_straight_down.xml", "envmap_sky.xml", "orthographic_instances.xml"] {
        let s = load_file(&root.join(name), &[("res".into(), "8".into())]).unwrap_or_else(|e| panic!("{name}: {e}"));
        let (img, _) = matte::render::renderer::render(
            &s.scene,
            &s.integrator,
            &s.camera,
            s.film.clone(),
            s.sampling.with_spp(4).with_seed(0),
            &|_, _| {},
        );
        assert!(img.pixels.iter().all(|p| p.is_finite()), "{name}: non-finite pixel");
        assert!(img.pixels.iter().any(|p| p.max_element() > 0.0), "{name}: black image");
    }
    let s = load_file(&root.join("sun_straight_down.xml"), &[]).unwrap();
    let light = &s.scene.emitters[0];
    let ground = s
        .scene
        .intersect(&Ray::new(Vec3::new(-0.8, 0.0, 5.0), Vec3::new(0.0, 0.0, -1.0), f32::INFINITY))
        .expect("sphere top");
    assert!((ground.p.z - 1.8).abs() < 1e-4, "the ray down meets the sphere first");
    let below = s
        .scene
        .intersect(&Ray::new(Vec3::new(-0.8, 0.0, 0.5), Vec3::new(0.0, 0.0, -1.0), f32::INFINITY))
        .expect("ground");
    let es = light.sample_direction(below.p, Vec2::ZERO, &s.scene.shapes).unwrap();
    assert!(s.scene.occluded(&s.scene.shadow_ray(&below, &es)), "the ground below the sphere is lit");
    let open = s
        .scene
        .intersect(&Ray::new(Vec3::new(0.2, -1.5, 0.5), Vec3::new(0.0, 0.0, -1.0), f32::INFINITY))
        .expect("ground");
    let es = light.sample_direction(open.p, Vec2::ZERO, &s.scene.shapes).unwrap();
    assert!(!s.scene.occluded(&s.scene.shadow_ray(&open, &es)), "open ground is shadowed");
}

/// `src/spectra/rawconstant.cpp`: `value` as a float (every channel) or a vector, unconverted.
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
    assert_eq!(refl(&v), Vec3::new(0.5, 0.25, 1.0));
    let f = load(&xml(r#"<texture type="rawconstant" name="reflectance"><float name="value" value="0.3"/></texture>"#))
        .unwrap();
    assert_eq!(refl(&f), Vec3::splat(0.3));
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
