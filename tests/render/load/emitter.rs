//! `<emitter>` (§2, §5, §9): emitter colours, textured `area` radiance, `point`, `spot`,
//! `directional` and `constant`, the `spot` texture lookup, `projector` irradiance
//! π·scale·T(uv)/(z² cos θ) and its image orientation, sampling weights, emitter selection in
//! Mitsuba's scene order and emitter positions mapped from the sample as Mitsuba maps them, and the
//! emitters' errors.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};
use matte_render::emitter::{Area, Constant, Directional, Emitter, Light, Point, Spot};
use matte_render::geometry::Ray;
use matte_render::load::{LoadedScene, load_file};

use super::references::{
    AREA_RADIANCE, CONSTANT_DEFAULT_RADIANCE, CONSTANT_SPECTRUM_1_RADIANCE, EMITTER_ORDER, POINT_DEFAULT_POSITION,
    POINT_POSITION_FROM_TO_WORLD, POINT_SPECTRUM_1_INTENSITY, RECTANGLE_SAMPLE_POSITION, TWO_TRIANGLE_SAMPLE_Z,
};
use super::{assert_body_err, assert_vec, close3, load, ok, temp_dir, with_sensor};
use crate::common::{SENSOR, assert_err_at, scene, write_exr};

fn one_emitter(xml: &str) -> Emitter {
    let s = ok(&with_sensor(xml));
    assert_eq!(s.scene.emitters.len(), 1);
    s.scene.emitters[0].clone()
}

#[test]
fn area_emitter_colours() {
    // §2: <spectrum value="1"> radiance is xyz_to_srgb(1,1,1) = (1.204794, 0.948291, 0.908916)
    // [verified]; <rgb> as is (no clamp); <float> grey; absent → white; a flat 0.5 sampled
    // spectrum → (0.6024, 0.4741, 0.4546) [verified]. Mitsuba's: `AREA_RADIANCE`.
    for &(prop, want) in AREA_RADIANCE {
        let want = Vec3::from(want);
        let s = ok(&with_sensor(&format!("<shape type=\"rectangle\"><emitter type=\"area\">{prop}</emitter></shape>")));
        let Emitter::Area(Area { shape, radiance }) = &s.scene.emitters[0] else { panic!("not area") };
        assert_eq!(*shape, 0);
        let radiance = radiance.eval(Vec2::ZERO);
        assert!(close3(radiance, want, 1e-4), "{prop}: {radiance} vs {want}");
    }
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

#[test]
fn point_spot_directional_constant() {
    // point: intensity default 1, position or to_world's translation (§9); Mitsuba's:
    // `POINT_POSITION_FROM_TO_WORLD`, `POINT_SPECTRUM_1_INTENSITY`, `POINT_DEFAULT_POSITION`.
    let Emitter::Point(Point { position, intensity }) =
        one_emitter("<emitter type=\"point\"><point name=\"position\" x=\"1\" y=\"2\" z=\"3\"/></emitter>")
    else {
        panic!()
    };
    assert_eq!((position, intensity), (Vec3::new(1.0, 2.0, 3.0), Vec3::ONE));
    let Emitter::Point(Point { position, intensity }) = one_emitter(
        "<emitter type=\"point\"><transform name=\"to_world\"><translate x=\"-1\" y=\"4\"/></transform>\
         <spectrum name=\"intensity\" value=\"1\"/></emitter>",
    ) else {
        panic!()
    };
    assert_eq!(position, Vec3::from(POINT_POSITION_FROM_TO_WORLD));
    assert_vec(intensity, POINT_SPECTRUM_1_INTENSITY.into(), 1e-5);
    // point at the origin by default.
    let Emitter::Point(Point { position, .. }) = one_emitter("<emitter type=\"point\"/>") else { panic!() };
    assert_eq!(position, Vec3::from(POINT_DEFAULT_POSITION));

    // spot: cutoff 20°, beam 0.75·cutoff = 15°, intensity 1, emits along to_world's +z.
    let Emitter::Spot(Spot { to_world, intensity, cutoff, beam_width, .. }) = one_emitter("<emitter type=\"spot\"/>")
    else {
        panic!()
    };
    assert!((cutoff - 20f32.to_radians()).abs() < 1e-6 && (beam_width - 15f32.to_radians()).abs() < 1e-6);
    assert_eq!((to_world, intensity), (glam::Affine3A::IDENTITY, Vec3::ONE));
    let Emitter::Spot(Spot { to_world, intensity, cutoff, beam_width, .. }) = one_emitter(
        "<emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"30\"/><rgb name=\"intensity\" value=\"8 8 12\"/>\
         <transform name=\"to_world\"><lookat origin=\"0,3,0\" target=\"0,0,0\" up=\"0,0,1\"/></transform></emitter>",
    ) else {
        panic!()
    };
    assert!((cutoff - 30f32.to_radians()).abs() < 1e-6 && (beam_width - 22.5f32.to_radians()).abs() < 1e-6);
    assert_eq!(intensity, Vec3::new(8.0, 8.0, 12.0));
    assert_vec(to_world.transform_vector3(Vec3::Z), Vec3::NEG_Y, 1e-6);
    assert_vec(to_world.translation.into(), Vec3::new(0.0, 3.0, 0.0), 1e-6);
    let Emitter::Spot(Spot { cutoff, beam_width, .. }) =
        one_emitter("<emitter type=\"spot\"><float name=\"beam_width\" value=\"5\"/></emitter>")
    else {
        panic!()
    };
    assert!((cutoff - 20f32.to_radians()).abs() < 1e-6 && (beam_width - 5f32.to_radians()).abs() < 1e-6);

    // directional: the direction light travels (normalised), or to_world's +z; irradiance 1.
    let Emitter::Directional(Directional { direction, irradiance }) =
        one_emitter("<emitter type=\"directional\"><vector name=\"direction\" x=\"0\" y=\"0\" z=\"-2\"/></emitter>")
    else {
        panic!()
    };
    assert_eq!((direction, irradiance), (Vec3::NEG_Z, Vec3::ONE));
    let Emitter::Directional(Directional { direction, .. }) = one_emitter("<emitter type=\"directional\"/>") else {
        panic!()
    };
    assert_eq!(direction, Vec3::Z);
    let Emitter::Directional(Directional { direction, irradiance }) = one_emitter(
        "<emitter type=\"directional\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"90\"/></transform>\
         <rgb name=\"irradiance\" value=\"0.4 0.35 0.3\"/></emitter>",
    ) else {
        panic!()
    };
    // Right-handed rotation: +90° about x takes +y to +z, so +z to −y (§3).
    assert_vec(direction, Vec3::NEG_Y, 1e-6);
    assert_eq!(irradiance, Vec3::new(0.4, 0.35, 0.3));

    // constant: radiance 1; the environment; to_world is accepted and changes nothing (Mitsuba's:
    // `CONSTANT_DEFAULT_RADIANCE`, `CONSTANT_SPECTRUM_1_RADIANCE`).
    let s = ok(&with_sensor(
        "<shape type=\"sphere\"/><emitter type=\"constant\"><transform name=\"to_world\"><rotate y=\"1\" angle=\"30\"/></transform></emitter>",
    ));
    assert_eq!(s.scene.environment, Some(0));
    let Emitter::Constant(Constant { radiance }) = s.scene.emitters[0] else { panic!() };
    assert_eq!(radiance, Vec3::from(CONSTANT_DEFAULT_RADIANCE));
    let Emitter::Constant(Constant { radiance }) =
        one_emitter("<emitter type=\"constant\"><spectrum name=\"radiance\" value=\"1\"/></emitter>")
    else {
        panic!()
    };
    assert_vec(radiance, CONSTANT_SPECTRUM_1_RADIANCE.into(), 1e-5);
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

#[test]
fn sampling_weights_set_the_selection_pmf() {
    // §9: pmf ∝ sampling_weight (3 and 1 → 0.75 and 0.25); the constant emitter's direction
    // density is 1/(4π) times its pmf.
    let s = ok(&with_sensor(
        "<emitter type=\"constant\"><float name=\"sampling_weight\" value=\"3\"/></emitter><emitter type=\"point\"/>",
    ));
    let env = s.scene.environment.expect("environment");
    let pdf = s.scene.pdf_emitter_direction(Vec3::ZERO, env, None);
    assert!((pdf - 0.75 / (4.0 * PI)).abs() < 1e-7, "{pdf}");
    // Uniform when all weights are 1 (area emitters count one each).
    let s = ok(&with_sensor(
        "<emitter type=\"constant\"/><emitter type=\"point\"/><shape type=\"sphere\"><emitter type=\"area\"/></shape>",
    ));
    let pdf = s.scene.pdf_emitter_direction(Vec3::ZERO, s.scene.environment.unwrap(), None);
    assert!((pdf - 1.0 / 3.0 / (4.0 * PI)).abs() < 1e-7, "{pdf}");
}

#[test]
fn emitter_errors() {
    assert_body_err("<emitter type=\"sunsky\"/>", 1, "unsupported emitter type \"sunsky\"");
    assert_body_err("<emitter type=\"envmap\"/>", 1, "missing property \"filename\"");
    // A top-level area emitter that no shape references is built and then left out, as
    // Mitsuba's Scene does (src/render/scene.cpp adds surface emitters only through shapes).
    assert_eq!(ok(&with_sensor("<emitter type=\"area\"/>")).scene.emitters.len(), 0);
    assert_body_err(
        "<emitter type=\"area\">\n<float name=\"bogus\" value=\"1\"/>\n</emitter>",
        2,
        "unreferenced property \"bogus\"",
    );
    assert_body_err(
        "<shape type=\"sphere\">\n<emitter type=\"area\">\n<transform name=\"to_world\"><translate x=\"1\"/></transform>\n</emitter>\n</shape>",
        3,
        "to_world",
    );
    assert_body_err(
        "<shape type=\"sphere\">\n<emitter type=\"point\"/>\n</shape>",
        2,
        "only an \"area\" emitter can be nested",
    );
    assert_body_err(
        "<emitter type=\"point\">\n<point name=\"position\" value=\"0 0 0\"/>\n<transform name=\"to_world\"><translate x=\"1\"/></transform>\n</emitter>",
        1,
        "either position or to_world",
    );
    assert_body_err(
        "<emitter type=\"directional\">\n<vector name=\"direction\" value=\"0 0 -1\"/>\n<transform name=\"to_world\"><translate x=\"1\"/></transform>\n</emitter>",
        1,
        "either direction or to_world",
    );
    assert_body_err(
        "<emitter type=\"directional\">\n<vector name=\"direction\" value=\"0 0 0\"/>\n</emitter>",
        1,
        "non-zero",
    );
    assert_body_err("<emitter type=\"spot\">\n<float name=\"beam_width\" value=\"30\"/>\n</emitter>", 1, "beam_width");
    assert_body_err("<emitter type=\"constant\"/>\n<emitter type=\"constant\"/>", 2, "only one environment");
    assert_body_err(
        "<emitter type=\"point\">\n<float name=\"sampling_weight\" value=\"-1\"/>\n</emitter>",
        2,
        "sampling_weight",
    );
    assert_body_err(
        "<emitter type=\"point\">\n<float name=\"radiance\" value=\"1\"/>\n</emitter>",
        2,
        "unreferenced property \"radiance\"",
    );
    assert_body_err("<emitter type=\"constant\">\n<float name=\"radiance\" value=\"inf\"/>\n</emitter>", 2, "finite");
    assert_body_err(
        "<emitter type=\"constant\">\n<string name=\"radiance\" value=\"white\"/>\n</emitter>",
        2,
        "wrong type",
    );
    assert_body_err(
        "<emitter type=\"constant\">\n<texture type=\"bitmap\" name=\"radiance\"><string name=\"filename\" value=\"x.png\"/></texture>\n</emitter>",
        1,
        "texture",
    );
}

/// Emitter selection lays the emitters on [0, 1) in Mitsuba 3.9.1's `Scene::emitters()` order:
/// top-level emitters and analytic shapes' area emitters as declared, then the meshes' area
/// emitters in reverse (docs/renderer-semantics.md §5). Oracle: that list for this scene from
/// `mi.load_string(..., parallel=False)`: e1, c, e2, p, a3, a2, a1 (`EMITTER_ORDER`).
#[test]
fn emitter_selection_follows_mitsubas_scene_order() {
    let area = |shape: &str, extra: &str| format!("<shape type=\"{shape}\">{extra}<emitter type=\"area\"/></shape>");
    let at_x = |x: i32| format!("<transform name=\"to_world\"><translate x=\"{x}\"/></transform>");
    let body = [
        area("sphere", &at_x(0)),
        area("rectangle", &at_x(1)),
        "<emitter type=\"constant\"/>".into(),
        area("sphere", &at_x(2)),
        area("rectangle", &at_x(3)),
        "<emitter type=\"point\"/>".into(),
        area("rectangle", &at_x(4)),
    ]
    .join("\n");
    let scene = ok(&with_sensor(&body)).scene;
    // Shapes in declaration order: 0 sphere, 1 rectangle, 2 sphere, 3 rectangle, 4 rectangle.
    let name = |i: usize| match &scene.emitters[i] {
        Emitter::Area(a) => format!("shape{}", a.shape),
        Emitter::Constant(_) => "constant".into(),
        Emitter::Point(_) => "point".into(),
        other => panic!("{other:?}"),
    };
    let picked: Vec<String> = (0..7).map(|k| name(scene.sample_emitter((k as f32 + 0.5) / 7.0).unwrap().0)).collect();
    assert_eq!(picked, EMITTER_ORDER);
    // The reused sample spans [0, 1) within each emitter's interval.
    let (_, pmf, reused) = scene.sample_emitter(1.0 / 7.0 + 0.25 / 7.0).unwrap();
    assert!((pmf - 1.0 / 7.0).abs() < 1e-6 && (reused - 0.25).abs() < 1e-4, "{pmf} {reused}");
}

/// Emitter positions are drawn as Mitsuba maps the sample (§5): a rectangle maps u onto
/// `to_world · (2u − 1, 2v − 1, 0)` (`src/shapes/rectangle.cpp`); a mesh picks its triangle ∝
/// area with the second component (`Mesh::sample_position`). Mitsuba's positions:
/// `RECTANGLE_SAMPLE_POSITION`, `TWO_TRIANGLE_SAMPLE_Z`.
#[test]
fn emitter_positions_map_the_sample_as_mitsuba() {
    use matte_render::shape::Geometry;
    let scene = ok(&with_sensor(
        "<shape type=\"rectangle\"><transform name=\"to_world\"><scale x=\"2\" y=\"0.5\"/><rotate x=\"1\" angle=\"90\"/>\
         <translate z=\"3\"/></transform></shape>\
         <shape type=\"obj\"><string name=\"filename\" value=\"two.obj\"/></shape>"
            .replace("two.obj", &{
                let dir = temp_dir("mesh_sampling");
                // Triangle 0 (z = 0) has area 1/2, triangle 1 (z = 1) area 3/2: the cdf
                // splits at 1/4.
                std::fs::write(
                    dir.join("two.obj"),
                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 1\nv 8 0 1\nv 5 1 1\nf 1 2 3\nf 4 5 6\n",
                )
                    .unwrap();
                dir.join("two.obj").display().to_string()
            })
            .as_str(),
    ))
    .scene;
    let Geometry::Triangles(rect) = &scene.shapes[0].geometry else { panic!() };
    // scale, then +90° about x: (x, y, 0) → (2x, 0, 0.5y), then z + 3; the normal is −y.
    for drawn in RECTANGLE_SAMPLE_POSITION {
        let (p, n, uv) = rect.sample_position(Vec2::from(drawn.u)).unwrap();
        let want = Vec3::from(drawn.p);
        assert!((p - want).abs().max_element() < 1e-5, "{p} {want}");
        assert!((n - Vec3::from(drawn.n)).abs().max_element() < 1e-6, "{n}");
        assert_eq!(uv, Vec2::from(drawn.uv));
    }
    let Geometry::Triangles(mesh) = &scene.shapes[1].geometry else { panic!() };
    let on = |p: Vec3, z: f32| (p.z - z).abs() < 1e-6;
    // The first component alone never decides the triangle (z = 0 or 1); the second does.
    for &(u, z) in TWO_TRIANGLE_SAMPLE_Z {
        assert!(on(mesh.sample_position(Vec2::from(u)).unwrap().0, z), "{u:?}");
    }
}
