//! Mesh attributes: PLY properties grouped and named as Mitsuba 3.9.1 does
//! (`src/shapes/ply.h`, `find_other_fields`), and the `mesh_attribute` texture
//! (`src/textures/mesh_attribute.cpp`, `Mesh::eval_attribute*` in `src/render/mesh.cpp`):
//! vertex attributes interpolated with the barycentrics, face attributes per triangle, times
//! `scale`. Oracles: the naming rules and values worked out by hand; vertex colours that are
//! a linear function of the position, so any correct interpolation reproduces that function.

use glam::{Mat4, Vec3};
use matte_render::bsdf::Bsdf;
use matte_render::geometry::Ray;
use matte_render::load::load_file;
use matte_scene_file::mesh::{MeshOptions, load_ply};
use std::path::{Path, PathBuf};

/// A unit square as one quad (0 1 2 3) plus a triangle (1 4 2) to its right, in z = 0.
/// Vertex colour (x, y, 0.5), heat = x + y; uv_x/uv_y is a 2-field group (ignored); the
/// faces carry weight_1 (→ face_weight) and tint_r/g/b (→ face_tint_color).
const PLY: &str = "ply
format ascii 1.0
element vertex 5
property float x
property float y
property float z
property float color_0
property float color_1
property float color_2
property float heat_0
property float uv_x
property float uv_y
element face 2
property list uchar int vertex_indices
property float weight_1
property float tint_r
property float tint_g
property float tint_b
end_header
0 0 0 0 0 0.5 0 9 9
1 0 0 1 0 0.5 1 9 9
1 1 0 1 1 0.5 2 9 9
0 1 0 0 1 0.5 1 9 9
2 0.5 0 2 0.5 0.5 2.5 9 9
4 0 1 2 3 0.25 0.1 0.2 0.3
3 1 4 2 0.75 0.4 0.5 0.6
";

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("matte_mesh_attributes_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn ply_properties_become_named_attributes() {
    let dir = temp_dir("ply");
    let path = dir.join("m.ply");
    std::fs::write(&path, PLY).unwrap();
    let m = load_ply(&path, &MeshOptions { to_world: Mat4::IDENTITY, ..MeshOptions::default() }).unwrap();
    let names: Vec<(&str, usize, bool)> = m.attributes.iter().map(|a| (a.name.as_str(), a.dim, a.per_face)).collect();
    assert_eq!(
        names,
        [("vertex_color", 3, false), ("vertex_heat", 1, false), ("face_weight", 1, true), ("face_tint_color", 3, true)]
    );
    // The quad is fan-triangulated into two triangles: its face values appear twice.
    assert_eq!(m.triangles.len(), 3);
    let weight = &m.attributes[2];
    assert_eq!(weight.values, [0.25, 0.25, 0.75]);
    assert_eq!(m.attributes[3].value(2), Vec3::new(0.4, 0.5, 0.6));
    assert_eq!(m.attributes[0].value(4), Vec3::new(2.0, 0.5, 0.5));
}

fn scene_with(dir: &Path, bsdf: &str) -> PathBuf {
    std::fs::write(dir.join("m.ply"), PLY).unwrap();
    let xml = format!(
        r#"<scene version="3.0.0">
<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="2"/></film></sensor>
<shape type="ply"><string name="filename" value="m.ply"/>
{bsdf}
</shape>
<shape type="sphere"><float name="radius" value="0.1"/><point name="center" x="0" y="0" z="-5"/></shape>
</scene>"#
    );
    let file = dir.join("s.xml");
    std::fs::write(&file, xml).unwrap();
    file
}

fn hit(s: &matte_render::load::LoadedScene, x: f32, y: f32) -> matte_render::shape::SurfaceInteraction {
    s.scene.intersect(&Ray::new(Vec3::new(x, y, 1.0), Vec3::NEG_Z, f32::INFINITY)).expect("hit")
}

#[test]
fn mesh_attribute_texture_interpolates_vertex_and_looks_up_face_values() {
    let dir = temp_dir("texture");
    let file = scene_with(
        &dir,
        r#"<bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"><string name="name" value="vertex_color"/><float name="scale" value="0.5"/></texture></bsdf>"#,
    );
    let s = load_file(&file, &[]).unwrap();
    for (x, y) in [(0.2f32, 0.7f32), (0.9, 0.1), (1.5, 0.5), (1.2, 0.45)] {
        let si = hit(&s, x, y);
        let Bsdf::Diffuse(d) = s.scene.bsdf(&si) else { panic!() };
        let got = d.reflectance.eval(&si);
        let expected = Vec3::new(x, y, 0.5) * 0.5;
        assert!((got - expected).abs().max_element() < 1e-5, "({x}, {y}): {got} vs {expected}");
    }

    // A face attribute as a blend weight (`eval_1`), shared by a top-level definition.
    let file = scene_with(
        &dir,
        r#"<bsdf type="blendbsdf"><texture type="mesh_attribute" name="weight"><string name="name" value="face_weight"/></texture><bsdf type="diffuse"/><bsdf type="conductor"/></bsdf>"#,
    );
    let s = load_file(&file, &[]).unwrap();
    for (x, y, w) in [(0.2f32, 0.7f32, 0.25f32), (0.7, 0.2, 0.25), (1.5, 0.5, 0.75)] {
        let si = hit(&s, x, y);
        let Bsdf::Blend(b) = s.scene.bsdf(&si) else { panic!() };
        assert_eq!(b.weight(&si), w, "({x}, {y})");
    }
}

/// The attribute must exist on the shape (Mitsuba throws at evaluation), the name must
/// contain `vertex_` or `face_` (Mitsuba's constructor), and only meshes have attributes.
#[test]
fn mesh_attribute_errors() {
    let dir = temp_dir("errors");
    let texture = |name: &str| {
        format!(
            r#"<bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"><string name="name" value="{name}"/></texture></bsdf>"#
        )
    };
    let text = |r: Result<matte_render::load::LoadedScene, matte_scene_file::SceneError>| match r {
        Ok(_) => panic!("expected an error"),
        Err(e) => e.to_string(),
    };
    let e = text(load_file(&scene_with(&dir, &texture("vertex_colour")), &[]));
    assert!(
        e.contains("s.xml:4:") && e.contains("no attribute \"vertex_colour\"") && e.contains("vertex_color"),
        "{e}"
    );
    let e = text(load_file(&scene_with(&dir, &texture("colour")), &[]));
    assert!(e.contains("s.xml:4:") && e.contains("must start with either"), "{e}");
    let sphere = dir.join("sphere.xml");
    std::fs::write(
        &sphere,
        format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n<shape type=\"sphere\">\n{}\n</shape>\n</scene>",
            texture("vertex_color")
        ),
    )
    .unwrap();
    let e = text(load_file(&sphere, &[]));
    assert!(e.contains("sphere.xml:4:") && e.contains("needs a mesh shape"), "{e}");
    assert!(!e.contains('\n'));
}
