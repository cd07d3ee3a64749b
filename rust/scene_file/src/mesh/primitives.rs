//! Mitsuba's built-in `rectangle` and `cube` shapes as triangle meshes, with exactly the vertex
//! buffers Mitsuba 3.9.1 builds (`src/shapes/rectangle.cpp`, `src/shapes/cube.cpp`; the cube's
//! buffers and the rectangle's uv / normals / triangle split were checked against
//! `mi.traverse` and ray queries in `scalar_rgb`).
//!
//! Both always carry per-vertex normals `normalize(M⁻ᵀ · n_local)`, even with
//! `face_normals = true` (Mitsuba ignores it for these two). Under a mirroring `to_world`
//! the winding normal therefore points opposite the shading normal, exactly as in Mitsuba:
//! a rectangle scaled by (−1, 2, 1) has `si.n = −z` but `sh_frame.n = +z`.
//! `flip_normals` is left to the renderer, as for every mesh (see [`super`]).

use super::options::MeshOptions;
use super::triangle_mesh::TriangleMesh;
use glam::{Mat3, Vec2, Vec3};

/// `[-1,1]² × {0}`, normal +z, uv = ((x+1)/2, (y+1)/2). Vertex i sits at
/// x = ±1 by bit 0 and y = ±1 by bit 1 of i; triangles (1,2,0), (1,3,2).
pub fn rectangle(opts: &MeshOptions) -> TriangleMesh {
    let nm = opts.normal_matrix();
    let uvs: Vec<Vec2> = (0..4).map(|i| Vec2::new((i & 1) as f32, ((i >> 1) & 1) as f32)).collect();
    let positions = uvs.iter().map(|uv| opts.point((2.0 * *uv - 1.0).extend(0.0))).collect();
    let triangles = vec![[1, 2, 0], [1, 3, 2]];
    let mut mesh = TriangleMesh { positions, normals: Vec::new(), uvs, triangles, attributes: Vec::new() };
    mesh.normals = vec![unit_normal(&nm, Vec3::Z, &mesh, 0); 4];
    mesh
}

/// The faces of Mitsuba's cube in buffer order: outward normal and the 4 corners. Corner k
/// gets uv (0,1), (1,1), (1,0), (0,0); the face's triangles are (0,1,2) and (3,0,2).
const CUBE_FACES: [(Vec3, [[f32; 3]; 4]); 6] = [
    (Vec3::NEG_Y, [[1., -1., -1.], [1., -1., 1.], [-1., -1., 1.], [-1., -1., -1.]]),
    (Vec3::Y, [[1., 1., -1.], [-1., 1., -1.], [-1., 1., 1.], [1., 1., 1.]]),
    (Vec3::X, [[1., -1., -1.], [1., 1., -1.], [1., 1., 1.], [1., -1., 1.]]),
    (Vec3::Z, [[1., -1., 1.], [1., 1., 1.], [-1., 1., 1.], [-1., -1., 1.]]),
    (Vec3::NEG_X, [[-1., -1., 1.], [-1., 1., 1.], [-1., 1., -1.], [-1., -1., -1.]]),
    (Vec3::NEG_Z, [[1., 1., -1.], [1., -1., -1.], [-1., -1., -1.], [-1., 1., -1.]]),
];

const CORNER_UV: [Vec2; 4] = [Vec2::new(0., 1.), Vec2::new(1., 1.), Vec2::new(1., 0.), Vec2::new(0., 0.)];

/// `[-1,1]³`: 24 vertices (4 per face, not shared), 12 triangles, flat outward normals,
/// per-face uv over the unit square.
pub fn cube(opts: &MeshOptions) -> TriangleMesh {
    let nm = opts.normal_matrix();
    let mut mesh = TriangleMesh::default();
    for (f, (normal, corners)) in CUBE_FACES.iter().enumerate() {
        let b = 4 * f as u32;
        mesh.positions.extend(corners.iter().map(|&c| opts.point(Vec3::from(c))));
        mesh.uvs.extend(CORNER_UV);
        mesh.triangles.extend([[b, b + 1, b + 2], [b + 3, b, b + 2]]);
        let n = unit_normal(&nm, *normal, &mesh, 2 * f);
        mesh.normals.extend([n; 4]);
    }
    mesh
}

/// `normalize(M⁻ᵀ n)`. Only a singular `to_world` (a flattened shape, never hit) makes it
/// non-finite; Mitsuba then stores NaN, here the winding normal of `tri` (or +z) is used so
/// that nothing downstream sees NaN.
fn unit_normal(nm: &Mat3, n: Vec3, mesh: &TriangleMesh, tri: usize) -> Vec3 {
    let w = (*nm * n).normalize();
    if w.is_finite() {
        return w;
    }
    let [a, b, c] = mesh.corners(tri);
    let g = (b - a).cross(c - a).normalize();
    if g.is_finite() { g } else { Vec3::Z }
}
