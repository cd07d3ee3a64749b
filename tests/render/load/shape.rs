//! `<shape>` (§3, §8): every shape type with its default BSDF, the analytic shapes' placement,
//! meshes from files, assets found through `<include>`, `<path>` and nested includes as Mitsuba
//! finds them, a referenced BSDF shared, `shapegroup`/`instance` placement, and the shapes' errors.

use std::path::Path;

use glam::Vec3;
use matte_render::geometry::Ray;
use matte_render::load::{load_file, load_str};

use super::references::{INCLUDED_PATH_OUTLIVES_ITS_FILE, NESTED_INCLUDES_FIND_THE_MESH};
use super::{
    FILE, assert_body_err, assert_vec, constant_reflectance, hit, load, ok, shape_bsdf, temp_dir, with_sensor,
};
use crate::common::{SENSOR, assert_err_at, assert_error_at, scene};

#[test]
fn every_shape_type_loads_with_default_bsdfs() {
    let s = ok(&with_sensor(
        "<shape type=\"sphere\"/><shape type=\"disk\"/><shape type=\"cylinder\"/><shape type=\"rectangle\"/><shape type=\"cube\"/>\
         <shape type=\"sphere\"><emitter type=\"area\"/></shape>\
         <shape type=\"sphere\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.1 0.2 0.3\"/></bsdf><emitter type=\"area\"/></shape>",
    ));
    let plugins: Vec<&str> = s.scene.shapes.iter().map(|sh| sh.plugin.as_str()).collect();
    assert_eq!(plugins, ["sphere", "disk", "cylinder", "rectangle", "cube", "sphere", "sphere"]);
    // §8: no BSDF → diffuse 0.5; emitter and no BSDF → diffuse 0 (black); an explicit one wins.
    for i in 0..5 {
        assert_eq!(constant_reflectance(shape_bsdf(&s, i)), Vec3::splat(0.5));
        assert_eq!(s.scene.shapes[i].emitter, None);
    }
    assert_eq!(constant_reflectance(shape_bsdf(&s, 5)), Vec3::ZERO);
    assert_eq!(constant_reflectance(shape_bsdf(&s, 6)), Vec3::new(0.1, 0.2, 0.3));
    assert_eq!(s.scene.shapes[5].emitter, Some(0));
    assert_eq!(s.scene.shapes[6].emitter, Some(1));
    assert_eq!(s.scene.emitters.len(), 2);
    // Rectangle: 2 triangles, cube: 12; each analytic shape is one primitive.
    assert_eq!(s.scene.primitive_count(), 5 + 2 + 12);
}

#[test]
fn sphere_center_radius_and_to_world() {
    // §3: to_world·T(center)·S(radius): centre (1,2,3) then translated by (0,0,−1) → (1,2,2).
    let s = ok(&with_sensor(
        "<shape type=\"sphere\"><point name=\"center\" x=\"1\" y=\"2\" z=\"3\"/><float name=\"radius\" value=\"0.5\"/>\
         <transform name=\"to_world\"><translate z=\"-1\"/></transform></shape>",
    ));
    let si = hit(&s, Vec3::new(1.0, 2.0, 10.0), Vec3::NEG_Z).expect("hit");
    assert!((si.t - 7.5).abs() < 1e-5, "{}", si.t);
    assert_vec(si.p, Vec3::new(1.0, 2.0, 2.5), 1e-5);
    assert_vec(si.n, Vec3::Z, 1e-5);
    assert_vec(si.sh_frame.n, Vec3::Z, 1e-5);
    assert!(hit(&s, Vec3::new(1.0, 2.49, 10.0), Vec3::NEG_Z).is_some());
    assert!(hit(&s, Vec3::new(1.0, 2.51, 10.0), Vec3::NEG_Z).is_none());
    // Radius from a uniform scale in to_world, and flip_normals → inward (§8).
    let s = ok(&with_sensor(
        "<shape type=\"sphere\"><boolean name=\"flip_normals\" value=\"true\"/>\
         <transform name=\"to_world\"><scale value=\"2\"/><translate x=\"5\"/></transform></shape>",
    ));
    let si = hit(&s, Vec3::new(0.0, 0.0, 0.0), Vec3::X).expect("hit");
    assert!((si.t - 3.0).abs() < 1e-5);
    assert_vec(si.sh_frame.n, Vec3::X, 1e-5); // inward at the near pole (outward is −x)
}

#[test]
fn cylinder_p0_p1_radius_without_caps() {
    let s = ok(&with_sensor(
        "<shape type=\"cylinder\"><point name=\"p0\" x=\"0\" y=\"0\" z=\"0\"/><point name=\"p1\" x=\"0\" y=\"2\" z=\"0\"/>\
         <float name=\"radius\" value=\"0.5\"/></shape>",
    ));
    let si = hit(&s, Vec3::new(5.0, 1.0, 0.0), Vec3::NEG_X).expect("hit");
    assert!((si.t - 4.5).abs() < 1e-5);
    assert_vec(si.p, Vec3::new(0.5, 1.0, 0.0), 1e-5);
    assert_vec(si.sh_frame.n, Vec3::X, 1e-5);
    // Outside [p0, p1] and along the axis (no caps): misses.
    assert!(hit(&s, Vec3::new(5.0, 2.1, 0.0), Vec3::NEG_X).is_none());
    assert!(hit(&s, Vec3::new(5.0, -0.1, 0.0), Vec3::NEG_X).is_none());
    assert!(hit(&s, Vec3::new(0.0, 5.0, 0.0), Vec3::NEG_Y).is_none());
    // Defaults p0 (0,0,0), p1 (0,0,1), radius 1, inside to_world.
    let s = ok(&with_sensor(
        "<shape type=\"cylinder\"><transform name=\"to_world\"><translate x=\"3\"/></transform></shape>",
    ));
    let si = hit(&s, Vec3::new(3.0, 5.0, 0.5), Vec3::NEG_Y).expect("hit");
    assert_vec(si.p, Vec3::new(3.0, 1.0, 0.5), 1e-5);
    assert!(hit(&s, Vec3::new(3.0, 5.0, 1.1), Vec3::NEG_Y).is_none());
}

#[test]
fn disk_rectangle_cube_and_flip_normals() {
    let s = ok(&with_sensor(
        "<shape type=\"disk\"><transform name=\"to_world\"><scale value=\"2\"/><translate z=\"1\"/></transform></shape>",
    ));
    let si = hit(&s, Vec3::new(1.5, 0.0, 5.0), Vec3::NEG_Z).expect("hit");
    assert!((si.t - 4.0).abs() < 1e-5);
    assert_vec(si.sh_frame.n, Vec3::Z, 1e-6);
    assert!(hit(&s, Vec3::new(1.5, 1.5, 5.0), Vec3::NEG_Z).is_none()); // r = 2.12 > 2
    let s = ok(&with_sensor("<shape type=\"disk\"><boolean name=\"flip_normals\" value=\"true\"/></shape>"));
    assert_vec(hit(&s, Vec3::new(0.2, 0.0, 5.0), Vec3::NEG_Z).expect("hit").sh_frame.n, Vec3::NEG_Z, 1e-6);

    // Rectangle [−1,1]² in z=0, +z normal; flip_normals negates n and sh_n (§8).
    let s = ok(&with_sensor(
        "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"3\"/></transform></shape>",
    ));
    let si = hit(&s, Vec3::new(2.5, -2.5, 4.0), Vec3::NEG_Z).expect("hit");
    assert_vec(si.p, Vec3::new(2.5, -2.5, 0.0), 1e-5);
    assert_vec(si.n, Vec3::Z, 1e-6);
    assert!(hit(&s, Vec3::new(3.1, 0.0, 4.0), Vec3::NEG_Z).is_none());
    let s = ok(&with_sensor("<shape type=\"rectangle\"><boolean name=\"flip_normals\" value=\"true\"/></shape>"));
    let si = hit(&s, Vec3::new(0.5, 0.5, 4.0), Vec3::NEG_Z).expect("hit");
    assert_vec(si.n, Vec3::NEG_Z, 1e-6);
    assert_vec(si.sh_frame.n, Vec3::NEG_Z, 1e-6);

    // Cube [−1,1]³; face_normals is accepted on the built-in meshes (Mitsuba's Mesh reads it).
    let s = ok(&with_sensor(
        "<shape type=\"cube\"><boolean name=\"face_normals\" value=\"true\"/>\
         <transform name=\"to_world\"><translate y=\"1\"/></transform></shape>\
         <shape type=\"rectangle\"><boolean name=\"face_normals\" value=\"true\"/>\
         <transform name=\"to_world\"><translate y=\"2\" z=\"-10\"/></transform></shape>",
    ));
    let si = hit(&s, Vec3::new(0.0, 1.5, 5.0), Vec3::NEG_Z).expect("hit");
    assert!((si.t - 4.0).abs() < 1e-5);
    assert_vec(si.n, Vec3::Z, 1e-6);
    assert!(hit(&s, Vec3::new(0.0, 2.1, 5.0), Vec3::NEG_Z).unwrap().p.z < -9.0);
}

const QUAD_OBJ: &str = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
const TRIANGLE_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

#[test]
fn obj_and_ply_meshes_from_files() {
    let dir = temp_dir("meshes");
    std::fs::create_dir_all(dir.join("m")).unwrap();
    std::fs::write(dir.join("m/quad.obj"), QUAD_OBJ).unwrap();
    std::fs::write(dir.join("tri.ply"), TRIANGLE_PLY).unwrap();
    let xml = with_sensor(
        "<shape type=\"obj\"><string name=\"filename\" value=\"m/quad.obj\"/><boolean name=\"face_normals\" value=\"true\"/>\
         <transform name=\"to_world\"><translate z=\"2\"/></transform></shape>\
         <shape type=\"ply\"><string name=\"filename\" value=\"tri.ply\"/><boolean name=\"flip_normals\" value=\"true\"/>\
         <transform name=\"to_world\"><scale value=\"2\"/><translate x=\"5\"/></transform></shape>",
    );
    // Relative file names resolve against the scene file's folder.
    let path = dir.join("scene.xml");
    std::fs::write(&path, &xml).unwrap();
    for s in [
        load_file(&path, &[]).unwrap_or_else(|e| panic!("{e}")),
        load_str(&xml, &path, &[]).unwrap_or_else(|e| panic!("{e}")),
    ] {
        assert_eq!(s.scene.shapes.len(), 2);
        assert_eq!(s.scene.primitive_count(), 3);
        // The quad (fan-triangulated, CCW seen from +z) moved to z = 2.
        let si = hit(&s, Vec3::new(0.5, 0.5, 10.0), Vec3::NEG_Z).expect("obj hit");
        assert!((si.t - 8.0).abs() < 1e-5);
        assert_vec(si.n, Vec3::Z, 1e-6);
        assert_eq!(si.shape, 0);
        // The triangle scaled by 2 and moved to x = 5; flipped normal.
        let si = hit(&s, Vec3::new(5.5, 0.5, -3.0), Vec3::Z).expect("ply hit");
        assert!((si.t - 3.0).abs() < 1e-5);
        assert_vec(si.n, Vec3::NEG_Z, 1e-6);
        assert!(hit(&s, Vec3::new(6.2, 1.2, -3.0), Vec3::Z).is_none()); // object space (0.6, 0.6): x + y > 1, outside
        assert_eq!(constant_reflectance(shape_bsdf(&s, 1)), Vec3::splat(0.5));
    }
}

const TRIANGLE_OBJ: &str = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";

#[test]
fn included_file_assets_resolve_against_the_main_scene() {
    // §1 pitfall: asset paths in an included file are NOT relative to that file.
    let dir = temp_dir("include");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::write(dir.join("quad.obj"), QUAD_OBJ).unwrap();
    std::fs::write(
        dir.join("sub/inc.xml"),
        "<scene version=\"3.0.0\">\n<shape type=\"obj\"><string name=\"filename\" value=\"quad.obj\"/></shape>\n</scene>",
    )
    .unwrap();
    let main = dir.join("main.xml");
    std::fs::write(&main, with_sensor("<include filename=\"sub/inc.xml\"/>")).unwrap();
    let s = load_file(&main, &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.scene.shapes.len(), 1);
    // And an error in the included file names that file and its line.
    std::fs::write(dir.join("sub/inc.xml"), "<scene version=\"3.0.0\">\n<shape type=\"obj\">\n<string name=\"filename\" value=\"nope.obj\"/>\n</shape>\n</scene>")
        .unwrap();
    let Err(e) = load_file(&main, &[]) else { panic!("expected an error") };
    assert_error_at(&e, &dir.join("sub/inc.xml"), 3, "nope.obj");
}

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
/// it does not find the scene's assets (Mitsuba on the same layout: `NESTED_INCLUDES_FIND_THE_MESH`,
/// `INCLUDED_PATH_OUTLIVES_ITS_FILE`).
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
    let hit = s.scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, f32::INFINITY)).is_some();
    assert_eq!(hit, NESTED_INCLUDES_FIND_THE_MESH);
    // mat.xml's `<path value="../meshes"/>` does not outlive mat.xml: Mitsuba reports
    // `OBJ file "tri.obj": file not found` here.
    std::fs::write(&file, main("tri.obj")).unwrap();
    let expired = load_file(&file, &[]);
    assert_eq!(expired.is_ok(), INCLUDED_PATH_OUTLIVES_ITS_FILE);
    assert_err_at(expired, &file, 4, "tri.obj");
    // An include that is nowhere: the error names the file the resolver fell back to.
    std::fs::write(dir.join("x/y/include/inc.xml"), inc.replace("mat.xml", "nothing.xml")).unwrap();
    assert_err_at(load_file(&file, &[]), &dir.join("x/y/include/inc.xml"), 3, "nothing.xml");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn referenced_bsdf_is_shared() {
    let s = ok(&with_sensor(
        "<bsdf type=\"diffuse\" id=\"red\"><rgb name=\"reflectance\" value=\"0.8 0.1 0.1\"/></bsdf>\
         <shape type=\"sphere\"><ref id=\"red\"/></shape><shape type=\"disk\"><ref id=\"red\"/></shape>\
         <shape type=\"cube\"><ref name=\"bsdf\" id=\"red\"/></shape>",
    ));
    assert_eq!(s.scene.bsdfs.len(), 1);
    assert!(s.scene.shapes.iter().all(|sh| sh.bsdf == 0));
    assert_eq!(constant_reflectance(&s.scene.bsdfs[0]), Vec3::new(0.8, 0.1, 0.1));
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

#[test]
fn shape_errors() {
    let dir = temp_dir("broken_meshes");
    std::fs::write(dir.join("bad_index.obj"), "v 0 0 0\nv 1 0 0\nf 1 2 7\n").unwrap();
    std::fs::write(dir.join("bad_number.obj"), "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(dir.join("short.ply"), TRIANGLE_PLY.replace("0 1 0\n", "")).unwrap();
    std::fs::write(dir.join("garbage.ply"), "this is not a ply file\n").unwrap();
    let path = dir.join("scene.xml");
    let mesh_err = |plugin: &str, file: &str, needle: &str| {
        let xml =
            with_sensor(&format!("<shape type=\"{plugin}\">\n<string name=\"filename\" value=\"{file}\"/>\n</shape>"));
        let Err(e) = load_str(&xml, &path, &[]) else { panic!("{file}: expected an error") };
        assert_error_at(&e, &path, 4, needle);
        assert!(e.to_string().contains(file), "{e}");
    };
    mesh_err("obj", "absent.obj", "cannot load mesh");
    mesh_err("ply", "absent.ply", "cannot load mesh");
    mesh_err("obj", "bad_index.obj", "bad_index.obj:3");
    mesh_err("obj", "bad_number.obj", "bad_number.obj:2");
    mesh_err("ply", "short.ply", "cannot load mesh");
    mesh_err("ply", "garbage.ply", "cannot load mesh");
    std::fs::write(dir.join("cut.serialized"), [0x1c, 0x04, 0x04, 0x00, 0x78]).unwrap();
    mesh_err("serialized", "cut.serialized", "truncated serialized file");
    let assets = crate::common::repo().join("mitsuba_scenes/assets/shapes.serialized");
    let serialized = |extra: &str| {
        with_sensor(&format!(
            "<shape type=\"serialized\">\n<string name=\"filename\" value=\"{}\"/>\n{extra}\n</shape>",
            assets.display()
        ))
    };
    let Err(e) = load_str(&serialized("<integer name=\"shape_index\" value=\"2\"/>"), &path, &[]) else {
        panic!("shape_index 2 loaded")
    };
    assert_error_at(&e, &path, 4, "shape_index 2 is out of range: the file holds 2 meshes (0..1)");
    let Err(e) = load_str(&serialized("<integer name=\"shape_index\" value=\"-1\"/>"), &path, &[]) else {
        panic!("shape_index -1 loaded")
    };
    assert_error_at(&e, &path, 5, "shape_index");
    let Err(e) = load_str(&serialized("<boolean name=\"flip_tex_coords\" value=\"true\"/>"), &path, &[]) else {
        panic!("flip_tex_coords accepted on serialized")
    };
    assert!(e.to_string().contains("flip_tex_coords"), "{e}");
    let loaded = load_str(&serialized("<integer name=\"shape_index\" value=\"1\"/>"), &path, &[]).unwrap();
    assert_eq!(loaded.scene.shapes.len(), 1);

    assert_body_err("<shape type=\"hair\"/>", 1, "unsupported shape type \"hair\"");
    assert_body_err("<shape type=\"obj\"/>", 1, "missing property \"filename\"");
    assert_body_err("<shape type=\"sphere\">\n<float name=\"radius\" value=\"-1\"/>\n</shape>", 2, "radius");
    assert_body_err("<shape type=\"sphere\">\n<float name=\"radius\" value=\"nan\"/>\n</shape>", 2, "radius");
    assert_body_err("<shape type=\"sphere\">\n<rgb name=\"center\" value=\"1 2 3\"/>\n</shape>", 2, "wrong type");
    // Beyond ±1e15 the BVH's f32 box areas overflow (matte's limit).
    assert_body_err(
        "<shape type=\"sphere\">\n<float name=\"radius\" value=\"1e20\"/>\n</shape>",
        1,
        "reaches coordinate",
    );
    assert_body_err(
        "<shape type=\"cube\">\n<transform name=\"to_world\"><translate x=\"1e16\"/></transform>\n</shape>",
        1,
        "reaches coordinate",
    );
    assert_body_err(
        "<shape type=\"sphere\">\n<boolean name=\"face_normals\" value=\"true\"/>\n</shape>",
        2,
        "unreferenced property \"face_normals\"",
    );
    assert_body_err(
        "<shape type=\"disk\">\n<float name=\"radius\" value=\"2\"/>\n</shape>",
        2,
        "unreferenced property \"radius\"",
    );
    assert_body_err(
        "<shape type=\"cylinder\">\n<point name=\"p0\" value=\"1 1 1\"/>\n<point name=\"p1\" value=\"1 1 1\"/>\n</shape>",
        1,
        "p0 ≠ p1",
    );
    assert_body_err(
        "<shape type=\"sphere\">\n<bsdf type=\"diffuse\"/>\n<bsdf type=\"diffuse\"/>\n</shape>",
        1,
        "more than one BSDF",
    );
    assert_body_err(
        "<shape type=\"sphere\">\n<emitter type=\"area\"/>\n<emitter type=\"area\"/>\n</shape>",
        1,
        "more than one emitter",
    );
    assert_body_err(
        "<shape type=\"sphere\">\n<sensor type=\"perspective\"/>\n</shape>",
        2,
        "cannot be nested in a shape",
    );
    // NaN anywhere in a transform is an error at its line (the parser's check).
    assert_body_err(
        "<shape type=\"rectangle\">\n<transform name=\"to_world\">\n<matrix value=\"1 0 0 0 0 nan 0 0 0 0 1 0 0 0 0 1\"/>\n</transform>\n</shape>",
        3,
        "NaN",
    );
    assert_body_err(
        "<shape type=\"rectangle\">\n<transform name=\"to_world\">\n<translate x=\"inf\"/>\n</transform>\n</shape>",
        3,
        "NaN or infinity",
    );
}
