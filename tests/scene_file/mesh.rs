//! Mesh loading (`rust/scene_file/src/mesh`): OBJ, PLY (ascii, binary LE/BE), `serialized`,
//! rectangle, cube.
//! Oracles: hand-written files with hand-derived expectations, closed forms (symmetry,
//! inverse-transpose normals), the verified smooth-normal value of `docs/renderer-semantics.md` §8, and the vertex buffers /
//! ray-query results of Mitsuba 3.9.1 `scalar_rgb` (`mi.traverse`, `scene.ray_intersect`).

use crate::common;

use glam::{Mat4, Quat, Vec2, Vec3};
use matte_scene_file::mesh::{
    MeshError, MeshOptions, TriangleMesh, cube, load_obj, load_ply, load_serialized, rectangle,
};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

// ---------------------------------------------------------------------------------------------
// helpers

/// A fresh directory under the system temp dir (one per call).
fn temp_dir() -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("matte-mesh-test-{}", std::process::id())).join(n.to_string());
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn temp_file(name: &str, contents: &[u8]) -> PathBuf {
    let path = temp_dir().join(name);
    std::fs::write(&path, contents).unwrap();
    path
}

fn obj(text: &str) -> PathBuf {
    temp_file("m.obj", text.as_bytes())
}

fn load(text: &str) -> TriangleMesh {
    load_obj(&obj(text), &MeshOptions::default()).unwrap()
}

fn obj_err(text: &str) -> (PathBuf, MeshError) {
    let p = obj(text);
    let e = load_obj(&p, &MeshOptions::default()).unwrap_err();
    (p, e)
}

fn close3(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol
}

fn assert_close3(a: Vec3, b: Vec3, tol: f32) {
    assert!(close3(a, b, tol), "{a} vs {b}");
}

/// Barycentric interpolation of per-vertex data at point `p` (lying on the mesh). Returns
/// the triangle index and the weights of its 3 corners.
fn locate(m: &TriangleMesh, p: Vec3) -> (usize, [f32; 3]) {
    for (i, t) in m.triangles.iter().enumerate() {
        let [a, b, c] = t.map(|k| m.positions[k as usize]);
        let n = (b - a).cross(c - a);
        if n.length_squared() == 0.0 || (p - a).dot(n).abs() > 1e-5 * n.length() {
            continue;
        }
        let area = n.length_squared();
        let w0 = (c - b).cross(p - b).dot(n) / area;
        let w1 = (a - c).cross(p - c).dot(n) / area;
        let w2 = (b - a).cross(p - a).dot(n) / area;
        if w0 >= -1e-6 && w1 >= -1e-6 && w2 >= -1e-6 {
            return (i, [w0, w1, w2]);
        }
    }
    panic!("point {p} is not on the mesh");
}

fn interpolate_normal(m: &TriangleMesh, p: Vec3) -> Vec3 {
    let (i, w) = locate(m, p);
    let t = m.triangles[i];
    (0..3).map(|k| m.normals[t[k] as usize] * w[k]).sum::<Vec3>().normalize()
}

fn interpolate_uv(m: &TriangleMesh, p: Vec3) -> (usize, Vec2) {
    let (i, w) = locate(m, p);
    let t = m.triangles[i];
    (i, (0..3).map(|k| m.uvs[t[k] as usize] * w[k]).sum())
}

fn winding_normal(m: &TriangleMesh, i: usize) -> Vec3 {
    let [a, b, c] = m.corners(i);
    (b - a).cross(c - a).normalize()
}

fn all_unit(normals: &[Vec3]) -> bool {
    normals.iter().all(|n| n.is_finite() && (n.length() - 1.0).abs() < 1e-5)
}

const CUBE8: &str = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
                     f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

// ---------------------------------------------------------------------------------------------
// OBJ

#[test]
fn obj_positions_are_transformed_to_world() {
    let p = obj("v 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n");
    let to_world = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0)) * Mat4::from_scale(Vec3::new(2.0, 3.0, 4.0));
    let m = load_obj(&p, &MeshOptions { to_world, ..Default::default() }).unwrap();
    assert_eq!(m.positions, vec![Vec3::new(3.0, 2.0, 3.0), Vec3::new(1.0, 5.0, 3.0), Vec3::new(1.0, 2.0, 7.0)]);
    assert_eq!(m.triangles, vec![[0, 1, 2]]);
    assert!(m.uvs.is_empty());
}

#[test]
fn obj_flips_v_by_default_and_not_when_asked() {
    let p = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25 0.2\nvt 0.5 1\nvt 1 0 0.7\nf 1/1 2/2 3/3\n");
    let m = load_obj(&p, &MeshOptions::default()).unwrap();
    assert_eq!(m.uvs, vec![Vec2::new(0.25, 0.8), Vec2::new(0.5, 0.0), Vec2::new(1.0, 1.0)]);
    let m = load_obj(&p, &MeshOptions { flip_tex_coords: Some(false), ..Default::default() }).unwrap();
    assert_eq!(m.uvs, vec![Vec2::new(0.25, 0.2), Vec2::new(0.5, 1.0), Vec2::new(1.0, 0.0)]);
}

#[test]
fn obj_shares_vertices_only_for_equal_index_triples() {
    let v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\n";
    let m = load(&format!("{v}f 1/1 2/1 3/1\nf 1/1 3/1 4/1\n"));
    assert_eq!(m.positions.len(), 4);
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    // Same position, different vt → a new vertex, numbered in order of first use.
    let m = load(&format!("{v}f 1/1 2/1 3/1\nf 1/2 3/1 4/1\n"));
    assert_eq!(m.positions.len(), 5);
    assert_eq!(m.triangles, vec![[0, 1, 2], [3, 2, 4]]);
    assert_eq!(m.positions[3], m.positions[0]);
    assert_eq!(m.uvs[3], Vec2::new(1.0, 0.0));
    // Equal positions from different `v` lines are NOT merged.
    let m = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0\nf 1 2 3\nf 4 3 2\n");
    assert_eq!(m.positions.len(), 4);
    assert_eq!(m.triangles, vec![[0, 1, 2], [3, 2, 1]]);
}

#[test]
fn obj_fan_triangulates_polygons() {
    let m = load("v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 3 0\nv -1 1 0\nf 1 2 3 4 5\n");
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
}

#[test]
fn obj_accepts_all_corner_forms_and_relative_indices() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n\
                f 1/1/1 2/2/1 3/3/1\nf 1//1 2//1 3//1\nf -3/-3/-1 -2/-2/-1 -1/-1/-1\n\
                v 5 0 0\nv 6 0 0\nv 5 1 0\nf -3 -2 -1\n";
    let m = load(text);
    // Triples (1,1,1),(2,2,1),(3,3,1) | (1,0,1),(2,0,1),(3,0,1) | = first | (4,0,0),(5,0,0),(6,0,0)
    assert_eq!(m.triangles, vec![[0, 1, 2], [3, 4, 5], [0, 1, 2], [6, 7, 8]]);
    assert_eq!(m.positions[6..], [Vec3::new(5.0, 0.0, 0.0), Vec3::new(6.0, 0.0, 0.0), Vec3::new(5.0, 1.0, 0.0)]);
    // Corners without vt get uv (0, 0) once the mesh has texture coordinates.
    assert_eq!(m.uvs[3], Vec2::ZERO);
    assert_eq!(m.uvs[1], Vec2::new(1.0, 1.0));
}

#[test]
fn obj_smooth_normals_match_mitsuba_cube_corner() {
    // §8 [verified]: 8-vertex cube, no vn; Mitsuba's shading normal at (0.9, 0.9, 1) on the top
    // face is (0.556, 0.556, 0.618).
    // Generated by tests/scene_file/mesh/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    let m = load(CUBE8);
    assert_eq!(m.positions.len(), 8);
    assert_close3(interpolate_normal(&m, Vec3::new(0.9, 0.9, 1.0)), Vec3::new(0.556, 0.556, 0.618), 1e-3);
    // By symmetry every corner normal is the corner direction (each face adds 90°).
    for (p, n) in m.positions.iter().zip(&m.normals) {
        assert_close3(*n, p.normalize(), 1e-6);
    }
}

#[test]
fn obj_smooth_normals_are_computed_in_world_space() {
    // Under a non-uniform scale the faces stay axis-aligned squares-turned-rectangles, each
    // still adding 90° at a corner: the world-space smooth normal is still the diagonal
    // (±1,±1,±1)/√3. (Object-space normals pushed through M⁻ᵀ would be ∝ (1, 1, 1/4).)
    let to_world = Mat4::from_scale(Vec3::new(1.0, 1.0, 4.0));
    let m = load_obj(&obj(CUBE8), &MeshOptions { to_world, ..Default::default() }).unwrap();
    for (p, n) in m.positions.iter().zip(&m.normals) {
        assert_close3(*n, p.signum() / 3f32.sqrt(), 1e-6);
    }
}

#[test]
fn obj_file_normals_use_the_inverse_transpose() {
    let p = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 1 1 0\nvn 0 0 -3\nf 1//1 2//2 3//2\n");
    let m = load_obj(&p, &MeshOptions { to_world: Mat4::from_scale(Vec3::new(2.0, 1.0, 1.0)), ..Default::default() })
        .unwrap();
    assert_close3(m.normals[0], Vec3::new(0.5, 1.0, 0.0).normalize(), 1e-6);
    assert_close3(m.normals[1], Vec3::NEG_Z, 1e-6);
    // Rotation + translation: normals rotate, ignore the translation.
    let rot = Quat::from_rotation_z(std::f32::consts::FRAC_PI_2);
    let to_world = Mat4::from_rotation_translation(rot, Vec3::new(5.0, 6.0, 7.0));
    let m = load_obj(&p, &MeshOptions { to_world, ..Default::default() }).unwrap();
    assert_close3(m.normals[0], Vec3::new(-1.0, 1.0, 0.0).normalize(), 1e-6);
    assert_close3(m.positions[1], Vec3::new(5.0, 7.0, 7.0), 1e-6);
}

#[test]
fn face_normals_drop_all_vertex_normals() {
    for text in [CUBE8, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n"] {
        let m = load_obj(&obj(text), &MeshOptions { face_normals: true, ..Default::default() }).unwrap();
        assert!(m.normals.is_empty());
    }
}

#[test]
fn flip_normals_leaves_the_data_alone() {
    // Mitsuba negates n and sh_n at query time (mesh.cpp); the loader must not flip too.
    let p = obj(CUBE8);
    let a = load_obj(&p, &MeshOptions::default()).unwrap();
    let b = load_obj(&p, &MeshOptions { flip_normals: true, ..Default::default() }).unwrap();
    assert_eq!(a, b);
}

#[test]
fn degenerate_triangles_are_kept_without_nan_normals() {
    let m = load("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n");
    assert_eq!(m.triangles.len(), 2);
    assert!(all_unit(&m.normals));
    assert_close3(m.normals[0], Vec3::Z, 1e-6);
    // Vertex 3 (index 2) only touches the zero-area triangle: Mitsuba's placeholder (1,0,0).
    // Generated by tests/scene_file/mesh/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    assert_eq!(m.normals[2], Vec3::X);
    let m = load("v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 3\nf 1 1 1\n");
    assert!(all_unit(&m.normals));
    assert_eq!(m.surface_area(), 0.0);
}

#[test]
fn corners_without_vn_get_smooth_normals_when_others_have_one() {
    let m = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 1 0 0\nf 1//1 2//1 3//1\nf 2 4 3\n");
    assert_eq!(m.positions.len(), 6);
    assert_eq!(m.normals[..3], [Vec3::X; 3]);
    assert!(all_unit(&m.normals));
    assert_close3(m.normals[4], Vec3::Z, 1e-6);
}

#[test]
fn obj_errors_name_file_line_and_problem() {
    let cases: &[(&str, usize, &str)] = &[
        ("v 0 0 0\nv 1 2\n", 2, "could not parse"),
        ("v 0 0 0\nvt 0.5\n", 2, "could not parse"),
        ("v 0 0 0\nvn 1 x 0\n", 2, "could not parse"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 a 3\n", 4, "could not parse"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", 4, "could not parse"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n", 5, "invalid vertex"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "invalid vertex index 0"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", 4, "invalid vertex index -4"),
        ("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", 1, "invalid vertex"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", 5, "invalid texture coordinate 2"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", 4, "invalid normal 1"),
        ("v 0 0 0\nv nan 0 0\n", 2, "invalid vertex position"),
        ("v 0 0 inf\n", 1, "invalid vertex position"),
        ("v 0 0 0\nvn 0 0 0\n", 2, "invalid vertex normal"),
        ("vt nan 0\n", 1, "invalid texture coordinate"),
    ];
    for &(text, line, what) in cases {
        let (p, e) = obj_err(text);
        assert_eq!(e.path, p, "{text:?}");
        assert_eq!(e.line, Some(line), "{text:?}: {e}");
        assert!(e.message.contains(what), "{text:?}: {e}");
        let shown = e.to_string();
        assert!(shown.contains(&p.display().to_string()) && shown.contains(&format!(":{line}:")), "{shown}");
    }
}

#[test]
fn obj_without_triangles_or_file_is_an_error() {
    for text in ["", "# nothing\nv 0 0 0\n", "v 0 0 0\nv 1 0 0\nf 1 2\n"] {
        let (_, e) = obj_err(text);
        assert!(e.message.contains("no triangles"), "{e}");
    }
    let missing = Path::new("/nonexistent/dir/missing.obj");
    let e = load_obj(missing, &MeshOptions::default()).unwrap_err();
    assert_eq!(e.path, missing);
    assert!(e.to_string().contains("missing.obj"), "{e}");
}

#[test]
fn obj_ignores_other_statements_and_crlf() {
    let m = load(
        "# comment\r\nmtllib x.mtl\r\no thing\r\ng grp\r\ns 1\r\nusemtl red\r\n  v 0 0 0 1\r\nv 1 0 0 # x\r\nv\t0 1 0\r\nf 1 2 3 # a triangle\r\n",
    );
    assert_eq!(m.positions, vec![Vec3::ZERO, Vec3::X, Vec3::Y]);
    assert_eq!(m.triangles, vec![[0, 1, 2]]);
}

// ---------------------------------------------------------------------------------------------
// PLY

/// A quad (fan-triangulated) + a triangle, with normals and uv.
const PLY_VERTS: [[f32; 8]; 5] = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.25],
    [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.25],
    [1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    [0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0],
    [0.5, 0.5, 1.0, 0.0, 1.0, 0.0, 0.5, 0.5],
];
const PLY_FACES: [&[i32]; 2] = [&[0, 1, 2, 3], &[3, 2, 4]];

fn ply_header(format: &str, uv: (&str, &str), index: &str) -> String {
    format!(
        "ply\nformat {format} 1.0\ncomment test\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n\
         property float nx\nproperty float ny\nproperty float nz\nproperty float {}\nproperty float {}\n\
         element face 2\nproperty list uchar int {index}\nend_header\n",
        uv.0, uv.1
    )
}

fn ply_ascii(uv: (&str, &str), index: &str) -> Vec<u8> {
    let mut s = ply_header("ascii", uv, index);
    for v in PLY_VERTS {
        s += &v.map(|x| x.to_string()).join(" ");
        s += "\n";
    }
    for f in PLY_FACES {
        s += &format!("{} {}\n", f.len(), f.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(" "));
    }
    s.into_bytes()
}

fn ply_binary(big_endian: bool) -> Vec<u8> {
    let format = if big_endian { "binary_big_endian" } else { "binary_little_endian" };
    let mut b = ply_header(format, ("u", "v"), "vertex_indices").into_bytes();
    for v in PLY_VERTS {
        for x in v {
            b.extend(if big_endian { x.to_be_bytes() } else { x.to_le_bytes() });
        }
    }
    for f in PLY_FACES {
        b.push(f.len() as u8);
        for &i in f {
            b.extend(if big_endian { i.to_be_bytes() } else { i.to_le_bytes() });
        }
    }
    b
}

fn expected_ply() -> TriangleMesh {
    TriangleMesh {
        positions: PLY_VERTS.iter().map(|v| Vec3::new(v[0], v[1], v[2])).collect(),
        normals: PLY_VERTS.iter().map(|v| Vec3::new(v[3], v[4], v[5])).collect(),
        uvs: PLY_VERTS.iter().map(|v| Vec2::new(v[6], v[7])).collect(),
        triangles: vec![[0, 1, 2], [0, 2, 3], [3, 2, 4]],
        attributes: vec![],
    }
}

fn ply(bytes: &[u8]) -> PathBuf {
    temp_file("m.ply", bytes)
}

#[test]
fn ply_ascii_and_binary_give_the_same_mesh() {
    let opts = MeshOptions::default();
    for bytes in [ply_ascii(("u", "v"), "vertex_indices"), ply_binary(false), ply_binary(true)] {
        assert_eq!(load_ply(&ply(&bytes), &opts).unwrap(), expected_ply());
    }
}

#[test]
fn ply_texture_coordinate_names_and_flip() {
    for uv in [("s", "t"), ("texture_u", "texture_v")] {
        assert_eq!(load_ply(&ply(&ply_ascii(uv, "vertex_index")), &MeshOptions::default()).unwrap(), expected_ply());
    }
    let m =
        load_ply(&ply(&ply_binary(false)), &MeshOptions { flip_tex_coords: Some(true), ..Default::default() }).unwrap();
    assert_eq!(m.uvs[0], Vec2::new(0.0, 0.75));
    // u,v wins over s,t when both exist.
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n\
                property float s\nproperty float t\nproperty float u\nproperty float v\nproperty uchar red\n\
                element face 1\nproperty list uchar uint vertex_indices\nend_header\n\
                0 0 0 9 9 0.1 0.2 255\n1 0 0 9 9 0.3 0.4 0\n0 1 0 9 9 0.5 0.6 7\n3 0 1 2\n";
    let m = load_ply(&ply(text.as_bytes()), &MeshOptions::default()).unwrap();
    assert_eq!(m.uvs, vec![Vec2::new(0.1, 0.2), Vec2::new(0.3, 0.4), Vec2::new(0.5, 0.6)]);
}

#[test]
fn ply_without_normals_gets_smooth_ones_and_face_normals_drops_them() {
    let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
                element face 1\nproperty list uchar int vertex_index\nelement edge 1\nproperty int vertex1\n\
                property int vertex2\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n0 1\n";
    let p = ply(text.as_bytes());
    let m = load_ply(&p, &MeshOptions::default()).unwrap();
    assert_eq!(m.normals, vec![Vec3::Z; 4]);
    assert!(m.uvs.is_empty());
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    let m = load_ply(&ply(&ply_binary(false)), &MeshOptions { face_normals: true, ..Default::default() }).unwrap();
    assert!(m.normals.is_empty());
    assert_eq!(m.uvs.len(), 5);
}

#[test]
fn ply_normals_and_positions_are_transformed() {
    let to_world = Mat4::from_translation(Vec3::new(0.0, 0.0, 1.0)) * Mat4::from_scale(Vec3::new(1.0, 1.0, 2.0));
    let m = load_ply(&ply(&ply_binary(true)), &MeshOptions { to_world, ..Default::default() }).unwrap();
    assert_eq!(m.positions[4], Vec3::new(0.5, 0.5, 3.0));
    assert_close3(m.normals[0], Vec3::Z, 1e-6);
    assert_close3(m.normals[4], Vec3::Y, 1e-6);
}

/// Binary (ply-rs's ascii reader rejects "nan" itself): vertex 1 has x = NaN.
fn nan_position_ply() -> Vec<u8> {
    let mut b = ply_binary(false);
    let first_vertex = ply_header("binary_little_endian", ("u", "v"), "vertex_indices").len();
    b[first_vertex + 32..first_vertex + 36].copy_from_slice(&f32::NAN.to_le_bytes());
    b
}

#[test]
fn ply_errors_name_the_file_and_problem() {
    let head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    let faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    let verts = "0 0 0\n1 0 0\n0 1 0\n";
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (b"ply\nformat foo 1.0\nend_header\n".to_vec(), "invalid PLY"),
        (b"not a ply file\n".to_vec(), "invalid PLY"),
        (format!("{head}{faces}{verts}3 0 1 3\n").into_bytes(), "vertex index 3 out of range"),
        (format!("{head}{faces}{verts}3 0 -1 2\n").into_bytes(), "vertex index -1 out of range"),
        (nan_position_ply(), "invalid position"),
        (format!("{head}{faces}{verts}").into_bytes(), "invalid PLY"),
        (format!("{head}end_header\n{verts}").into_bytes(), "no triangles"),
        (format!("{head}element face 0\nproperty list uchar int vertex_indices\nend_header\n{verts}").into_bytes(), "no triangles"),
        (format!("{head}element face 1\nproperty list uchar int foo\nend_header\n{verts}3 0 1 2\n").into_bytes(), "vertex_index"),
        (format!("{head}element face 1\nproperty list uchar float vertex_indices\nend_header\n{verts}3 0 1 2\n").into_bytes(), "invalid PLY"),
        (
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty int x\nproperty float y\nproperty float z\nelement face 1\n\
             property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
                .as_bytes()
                .to_vec(),
            "invalid PLY",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nelement face 1\n\
             property list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n"
                .as_bytes()
                .to_vec(),
            "no \"z\" property",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
             property float nx\nproperty float ny\nproperty float nz\nelement face 1\n\
             property list uchar int vertex_indices\nend_header\n0 0 0 0 0 0\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n"
                .as_bytes()
                .to_vec(),
            "invalid normal",
        ),
    ];
    for (bytes, what) in cases {
        let p = ply(&bytes);
        let e = load_ply(&p, &MeshOptions::default()).unwrap_err();
        assert_eq!(e.path, p);
        assert!(e.message.contains(what), "{}: expected {what:?}, got {e}", String::from_utf8_lossy(&bytes));
    }
    // Binary: truncated payload and trailing bytes.
    let full = ply_binary(false);
    for bytes in [&full[..full.len() - 3], &[full.as_slice(), &[0u8; 4]].concat()[..]] {
        let e = load_ply(&ply(bytes), &MeshOptions::default()).unwrap_err();
        assert!(e.message.contains("PLY"), "{e}");
    }
    let e = load_ply(Path::new("/nonexistent/m.ply"), &MeshOptions::default()).unwrap_err();
    assert!(e.to_string().contains("/nonexistent/m.ply"), "{e}");
}

// ---------------------------------------------------------------------------------------------
// rectangle and cube, checked against Mitsuba 3.9.1 scalar_rgb

/// Positions, normals, uvs, faces.
type Buffers = (Vec<[f32; 3]>, Vec<[f32; 3]>, Vec<[f32; 2]>, Vec<[u32; 3]>);

/// `mi.traverse(mi.load_dict({'type': 'cube'}))` vertex_positions / vertex_normals /
/// vertex_texcoords / faces, verbatim.
/// Generated by tests/scene_file/mesh/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
fn mitsuba_cube() -> Buffers {
    let pos = vec![
        [1., -1., -1.],
        [1., -1., 1.],
        [-1., -1., 1.],
        [-1., -1., -1.],
        [1., 1., -1.],
        [-1., 1., -1.],
        [-1., 1., 1.],
        [1., 1., 1.],
        [1., -1., -1.],
        [1., 1., -1.],
        [1., 1., 1.],
        [1., -1., 1.],
        [1., -1., 1.],
        [1., 1., 1.],
        [-1., 1., 1.],
        [-1., -1., 1.],
        [-1., -1., 1.],
        [-1., 1., 1.],
        [-1., 1., -1.],
        [-1., -1., -1.],
        [1., 1., -1.],
        [1., -1., -1.],
        [-1., -1., -1.],
        [-1., 1., -1.],
    ];
    let nrm = [[0., -1., 0.], [0., 1., 0.], [1., 0., 0.], [0., 0., 1.], [-1., 0., 0.], [0., 0., -1.]]
        .iter()
        .flat_map(|n| [*n; 4])
        .collect();
    let uv = (0..6).flat_map(|_| [[0., 1.], [1., 1.], [1., 0.], [0., 0.]]).collect();
    let faces = vec![
        [0, 1, 2],
        [3, 0, 2],
        [4, 5, 6],
        [7, 4, 6],
        [8, 9, 10],
        [11, 8, 10],
        [12, 13, 14],
        [15, 12, 14],
        [16, 17, 18],
        [19, 16, 18],
        [20, 21, 22],
        [23, 20, 22],
    ];
    (pos, nrm, uv, faces)
}

#[test]
fn cube_matches_mitsuba_buffers() {
    let (pos, nrm, uv, faces) = mitsuba_cube();
    for face_normals in [false, true] {
        // Mitsuba's cube keeps its normals even with face_normals=true [verified].
        let m = cube(&MeshOptions { face_normals, ..Default::default() });
        assert_eq!(m.positions, pos.iter().map(|p| Vec3::from(*p)).collect::<Vec<_>>());
        assert_eq!(m.normals, nrm.iter().map(|p| Vec3::from(*p)).collect::<Vec<_>>());
        assert_eq!(m.uvs, uv.iter().map(|p| Vec2::from(*p)).collect::<Vec<_>>());
        assert_eq!(m.triangles, faces);
    }
    let m = cube(&MeshOptions::default());
    for i in 0..12 {
        // Counter-clockwise seen from outside: winding normal = stored outward normal.
        assert_close3(winding_normal(&m, i), m.normals[m.triangles[i][0] as usize], 1e-6);
    }
    assert_eq!(m.surface_area(), 24.0);
}

#[test]
fn cube_under_a_mirroring_transform_matches_mitsuba() {
    // to_world = scale(-1, 2, 1): Mitsuba's vertex_positions = M·p and vertex_normals with
    // +x and -x swapped between faces 2 and 4, the rest unchanged [verified].
    // Generated by tests/scene_file/mesh/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    let to_world = Mat4::from_scale(Vec3::new(-1.0, 2.0, 1.0));
    let m = cube(&MeshOptions { to_world, ..Default::default() });
    let (pos, ..) = mitsuba_cube();
    for (p, q) in m.positions.iter().zip(&pos) {
        assert_eq!(*p, Vec3::new(-q[0], 2.0 * q[1], q[2]));
    }
    let expect = [Vec3::NEG_Y, Vec3::Y, Vec3::NEG_X, Vec3::Z, Vec3::X, Vec3::NEG_Z];
    for (k, n) in m.normals.iter().enumerate() {
        assert_close3(*n, expect[k / 4], 1e-6);
    }
    assert_eq!(m.surface_area(), 2.0 * (2.0 * 4.0 + 2.0 * 4.0 + 2.0 * 2.0));
}

#[test]
fn rectangle_matches_mitsuba_ray_queries() {
    // Mitsuba: rays down -z at (x, y) on the default rectangle give uv ((x+1)/2, (y+1)/2),
    // n = sh_n = +z; prim_index 0 for both points [verified].
    // Generated by tests/scene_file/mesh/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    let m = rectangle(&MeshOptions::default());
    assert_eq!(m.positions.len(), 4);
    assert_eq!(m.normals, vec![Vec3::Z; 4]);
    for (p, uv) in [(Vec2::new(0.5, -0.5), Vec2::new(0.75, 0.25)), (Vec2::new(-0.6, 0.2), Vec2::new(0.2, 0.6))] {
        let (tri, got) = interpolate_uv(&m, p.extend(0.0));
        assert!((got - uv).abs().max_element() < 1e-6, "{got} vs {uv}");
        assert_close3(winding_normal(&m, tri), Vec3::Z, 1e-6);
    }
    assert_eq!(m.triangles, vec![[1, 2, 0], [1, 3, 2]]);
    assert_eq!(m.surface_area(), 4.0);

    // to_world = scale(-1, 2, 1) [verified]: (0.5,-0.5) → uv (0.25, 0.375), prim 0;
    // (-0.6, 0.2) → uv (0.8, 0.55), prim 1; si.n = -z (winding), sh_n = +z (M⁻ᵀ z).
    let m = rectangle(&MeshOptions { to_world: Mat4::from_scale(Vec3::new(-1.0, 2.0, 1.0)), ..Default::default() });
    for (p, uv, prim) in
        [(Vec2::new(0.5, -0.5), Vec2::new(0.25, 0.375), 0), (Vec2::new(-0.6, 0.2), Vec2::new(0.8, 0.55), 1)]
    {
        let (tri, got) = interpolate_uv(&m, p.extend(0.0));
        assert!((got - uv).abs().max_element() < 1e-6, "{got} vs {uv}");
        assert_eq!(tri, prim);
        assert_close3(winding_normal(&m, tri), Vec3::NEG_Z, 1e-6);
        assert_close3(interpolate_normal(&m, p.extend(0.0)), Vec3::Z, 1e-6);
    }
    assert_eq!(m.surface_area(), 8.0);
}

#[test]
fn primitives_never_produce_nan_normals() {
    let flat = MeshOptions { to_world: Mat4::from_scale(Vec3::new(1.0, 1.0, 0.0)), ..Default::default() };
    assert!(all_unit(&cube(&flat).normals));
    assert!(all_unit(&rectangle(&flat).normals));
}

#[test]
fn random_obj_and_ply_match_mitsuba_buffers() {
    // Mitsuba 3.9.1 loads a random OBJ (polygons of 3–5 corners, shared and unshared
    // v/vt triples, no normals → smooth ones) under a rotate·scale·translate to_world, with and
    // without face_normals, and writes it back as binary PLY (x y z nx ny nz s t) which it
    // loads again; its vertex buffers are the oracle. Skipped when the venv is absent.
    let Some(python) = common::mitsuba_python() else { return };
    let script = r#"
import sys, json, numpy as np, mitsuba as mi
mi.set_variant('scalar_rgb')
obj, ply, out_path = sys.argv[1:4]
rng = np.random.default_rng(1)
lines = ["v %.6f %.6f %.6f" % tuple(p) for p in rng.normal(size=(30, 3))]
lines += ["vt %.4f %.4f" % tuple(t) for t in rng.random((10, 2))]
for i in range(25):
    n = rng.integers(3, 6)
    idx = rng.choice(30, n, replace=False) + 1
    lines.append("f " + " ".join("%d/%d" % (a, b) for a, b in zip(idx, rng.integers(1, 11, n))))
open(obj, 'w').write("\n".join(lines) + "\n")
M = mi.ScalarTransform4f().translate([1, 2, 3]) @ mi.ScalarTransform4f().rotate([1, 1, 0], 30) @ mi.ScalarTransform4f().scale([1, 2, 0.5])
keys = ['vertex_positions', 'vertex_normals', 'vertex_texcoords', 'faces']
out = {'matrix': np.array(M.matrix).tolist()}
for fn in [False, True]:
    p = mi.traverse(mi.load_dict({'type': 'obj', 'filename': obj, 'to_world': M, 'face_normals': fn}))
    out['obj-%s' % fn] = {k: np.array(p[k]).tolist() for k in keys}
mi.load_dict({'type': 'obj', 'filename': obj, 'to_world': M}).write_ply(ply)
p = mi.traverse(mi.load_dict({'type': 'ply', 'filename': ply}))
out['ply'] = {k: np.array(p[k]).tolist() for k in keys}
json.dump(out, open(out_path, 'w'))
"#;
    let dir = temp_dir();
    let (objp, plyp, jsonp) = (dir.join("r.obj"), dir.join("r.ply"), dir.join("r.json"));
    let out = std::process::Command::new(python).arg("-c").arg(script).args([&objp, &plyp, &jsonp]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&jsonp).unwrap()).unwrap();
    let rows: [[f32; 4]; 4] = serde_json::from_value(j["matrix"].clone()).unwrap();
    let to_world = Mat4::from_cols_array_2d(&rows).transpose();
    let check = |key: &str, m: &TriangleMesh| {
        let get = |k: &str| -> Vec<f32> { serde_json::from_value(j[key][k].clone()).unwrap() };
        let faces: Vec<u32> = serde_json::from_value(j[key]["faces"].clone()).unwrap();
        assert_eq!(m.triangles.concat(), faces, "{key}");
        let (pos, nrm, uv) = (get("vertex_positions"), get("vertex_normals"), get("vertex_texcoords"));
        assert_eq!(m.positions.len() * 3, pos.len(), "{key}");
        assert_eq!(m.normals.len() * 3, nrm.len(), "{key}");
        for (i, p) in m.positions.iter().enumerate() {
            assert_close3(*p, Vec3::from_slice(&pos[3 * i..]), 1e-5);
            assert!((m.uvs[i] - Vec2::from_slice(&uv[2 * i..])).abs().max_element() <= 1e-6, "{key}");
        }
        for (i, n) in m.normals.iter().enumerate() {
            assert_close3(*n, Vec3::from_slice(&nrm[3 * i..]), 1e-5);
        }
    };
    for face_normals in [false, true] {
        let m = load_obj(&objp, &MeshOptions { to_world, face_normals, ..Default::default() }).unwrap();
        check(&format!("obj-{}", if face_normals { "True" } else { "False" }), &m);
    }
    check("ply", &load_ply(&plyp, &MeshOptions::default()).unwrap());
}

// ---------------------------------------------------------------------------------------------
// serialized, checked against Mitsuba 3.9.1 scalar_rgb (tests/scene_file/serialized/generate_reference.py)

fn serialized_dir() -> PathBuf {
    crate::common::repo().join("tests/scene_file/serialized")
}

#[test]
fn serialized_meshes_match_mitsuba_buffers() {
    let text = std::fs::read_to_string(serialized_dir().join("mitsuba_reference.json")).unwrap();
    let j: serde_json::Value = serde_json::from_str(&text).unwrap();
    let cases = j["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 7);
    for c in cases {
        let key = format!("{} #{} face_normals={}", c["file"], c["shape_index"], c["face_normals"]);
        let to_world = match c["to_world"].as_array() {
            Some(rows) => {
                let r: Vec<[f32; 4]> = rows.iter().map(|r| serde_json::from_value(r.clone()).unwrap()).collect();
                Mat4::from_cols_array_2d(&[r[0], r[1], r[2], r[3]]).transpose()
            }
            None => Mat4::IDENTITY,
        };
        let face_normals = c["face_normals"].as_bool().unwrap();
        let opts = MeshOptions { to_world, face_normals, ..Default::default() };
        let path = serialized_dir().join(c["file"].as_str().unwrap());
        let m = load_serialized(&path, c["shape_index"].as_i64().unwrap(), &opts).unwrap();
        let get =
            |k: &str| -> Vec<f32> { c.get(k).map(|v| serde_json::from_value(v.clone()).unwrap()).unwrap_or_default() };
        let faces: Vec<u32> = serde_json::from_value(c["faces"].clone()).unwrap();
        assert_eq!(m.triangles.concat(), faces, "{key}");
        let (pos, nrm, uv) = (get("vertex_positions"), get("vertex_normals"), get("vertex_texcoords"));
        assert_eq!(m.positions.len() * 3, pos.len(), "{key}");
        assert_eq!(m.normals.len() * 3, nrm.len(), "{key}");
        assert_eq!(m.uvs.len() * 2, uv.len(), "{key}");
        for (i, p) in m.positions.iter().enumerate() {
            assert_close3(*p, Vec3::from_slice(&pos[3 * i..]), 1e-5);
        }
        for (i, n) in m.normals.iter().enumerate() {
            // Smooth normals (meshes without file normals) are summed in another order.
            assert_close3(*n, Vec3::from_slice(&nrm[3 * i..]), 2e-5);
        }
        for (i, t) in m.uvs.iter().enumerate() {
            assert_eq!(*t, Vec2::from_slice(&uv[2 * i..]), "{key}");
        }
    }
}

/// One version-4 mesh (header and zlib stream), f32 positions only, written here byte by byte
/// from the format description.
fn serialized_mesh(name: &str, pos: &[[f32; 3]], tris: &[[u32; 3]]) -> Vec<u8> {
    use flate2::{Compression, write::ZlibEncoder};
    use std::io::Write;
    let mut body = Vec::new();
    body.extend(0x1000u32.to_le_bytes());
    body.extend(name.as_bytes());
    body.push(0);
    body.extend((pos.len() as u64).to_le_bytes());
    body.extend((tris.len() as u64).to_le_bytes());
    body.extend(pos.iter().flatten().flat_map(|c| c.to_le_bytes()));
    body.extend(tris.iter().flatten().flat_map(|i| i.to_le_bytes()));
    let mut z = ZlibEncoder::new(Vec::new(), Compression::default());
    z.write_all(&body).unwrap();
    let mut out = vec![0x1C, 0x04, 4, 0];
    out.extend(z.finish().unwrap());
    out
}

/// A valid file with two meshes (0 a triangle, 1 a quad) and the offset where mesh 1 starts.
fn two_mesh_file() -> (Vec<u8>, usize) {
    let mut file = serialized_mesh("tri", &[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]], &[[0, 1, 2]]);
    let second = file.len();
    file.extend(serialized_mesh(
        "quad",
        &[[0., 0., 1.], [1., 0., 1.], [1., 1., 1.], [0., 1., 1.]],
        &[[0, 1, 2], [0, 2, 3]],
    ));
    file.extend(0u64.to_le_bytes());
    file.extend((second as u64).to_le_bytes());
    file.extend(2u32.to_le_bytes());
    (file, second)
}

#[test]
fn serialized_shape_index_selects_the_mesh_through_the_dictionary() {
    let (bytes, _) = two_mesh_file();
    let path = temp_file("two.serialized", &bytes);
    let opts = MeshOptions::default();
    let m0 = load_serialized(&path, 0, &opts).unwrap();
    let m1 = load_serialized(&path, 1, &opts).unwrap();
    assert_eq!((m0.positions.len(), m0.triangles.len()), (3, 1));
    assert_eq!((m1.positions.len(), m1.triangles.len()), (4, 2));
    assert_eq!(m1.positions[2], Vec3::new(1., 1., 1.));
    // No file normals: smooth ones, here the flat +z of a planar mesh.
    assert!(m1.normals.iter().all(|n| *n == Vec3::Z));
}

#[test]
fn serialized_errors_name_the_file_and_problem() {
    let (bytes, second) = two_mesh_file();
    let err = |bytes: &[u8], index: i64| -> String {
        let path = temp_file("bad.serialized", bytes);
        let e = load_serialized(&path, index, &MeshOptions::default()).unwrap_err().to_string();
        assert!(e.starts_with(&path.display().to_string()), "{e}");
        assert!(!e.contains('\n'), "{e}");
        e
    };
    assert!(err(&bytes, 2).contains("shape_index 2 is out of range: the file holds 2 meshes (0..1)"));
    assert!(err(&bytes, -1).contains("shape_index must be nonnegative"));
    let mut v = bytes.clone();
    v[2] = 5;
    assert!(err(&v, 0).contains("unsupported serialized file version 5"));
    let mut v = bytes.clone();
    v[0] = 0;
    assert!(err(&v, 0).contains("not a serialized mesh file"));
    assert!(err(&bytes[..second / 2], 0).contains("truncated serialized file"));
    assert!(err(&bytes[..3], 0).contains("truncated serialized file"));
    // The dictionary points into the middle of mesh 0.
    let mut v = bytes.clone();
    let at = v.len() - 12;
    v[at..at + 8].copy_from_slice(&7u64.to_le_bytes());
    assert!(err(&v, 1).contains("does not point at a mesh header"));
    // A face index beyond the vertex count; a NaN position.
    let mut v = serialized_mesh("bad", &[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]], &[[0, 1, 3]]);
    v.extend(0u64.to_le_bytes());
    v.extend(1u32.to_le_bytes());
    assert!(err(&v, 0).contains("triangle 0: vertex index 3 out of range (mesh has 3 vertices)"));
    let mut v = serialized_mesh("nan", &[[0., f32::NAN, 0.], [1., 0., 0.], [0., 1., 0.]], &[[0, 1, 2]]);
    v.extend(0u64.to_le_bytes());
    v.extend(1u32.to_le_bytes());
    assert!(err(&v, 0).contains("vertex 0: invalid position data"));
    assert!(
        load_serialized(Path::new("/nonexistent/m.serialized"), 0, &MeshOptions::default())
            .unwrap_err()
            .to_string()
            .contains("/nonexistent/m.serialized")
    );
}

/// Every prefix of a valid file, and thousands of files with random bytes changed, load or
/// fail with a one-line error: never a panic, a huge allocation or an index out of range.
#[test]
fn serialized_loader_survives_truncation_and_corruption() {
    use rand::{Rng, SeedableRng};
    let (bytes, second) = two_mesh_file();
    for len in 0..bytes.len() {
        let path = temp_file("prefix.serialized", &bytes[..len]);
        for index in 0..3 {
            let r = std::panic::catch_unwind(|| load_serialized(&path, index, &MeshOptions::default()));
            let r = r.unwrap_or_else(|_| panic!("panic at prefix {len}, index {index}"));
            if len + 4 < second || index > 0 {
                // Mesh 0 cut short, or the dictionary gone: always an error.
                assert!(r.is_err(), "prefix {len} index {index} loaded");
            }
        }
    }
    let mut rng = rand_pcg::Pcg64::seed_from_u64(26);
    let dir = temp_dir();
    for trial in 0..3000 {
        let mut v = bytes.clone();
        for _ in 0..rng.random_range(1..6) {
            let i = rng.random_range(0..v.len());
            v[i] = rng.random();
        }
        let path = dir.join(format!("fuzz{}.serialized", trial % 8));
        std::fs::write(&path, &v).unwrap();
        for index in 0..3 {
            let r = std::panic::catch_unwind(|| load_serialized(&path, index, &MeshOptions::default()));
            match r.unwrap_or_else(|_| panic!("panic on trial {trial}, index {index}")) {
                Ok(m) => {
                    assert!(m.positions.iter().all(|p| p.is_finite()));
                    assert!(m.triangles.iter().flatten().all(|&i| (i as usize) < m.positions.len()));
                    assert!(m.normals.iter().all(|n| n.is_finite()));
                }
                Err(e) => assert!(!e.to_string().contains('\n'), "{e}"),
            }
        }
    }
}
