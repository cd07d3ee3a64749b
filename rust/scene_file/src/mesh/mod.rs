//! Triangle meshes in world space: the `obj`, `ply`, `serialized`, `rectangle` and `cube` shapes
//! of Mitsuba 3.9.1 (`src/shapes/{obj,ply,serialized,rectangle,cube}.cpp`, `src/render/mesh.cpp`), loaded the way
//! Mitsuba loads them (`docs/renderer-semantics.md` §8):
//!
//! 1. positions × `to_world` (affine: the bottom matrix row is ignored, as for Mitsuba's
//!    `AffineTransform4f`);
//! 2. file normals × the inverse transpose of `to_world`, then normalised;
//! 3. a file without normals (and `face_normals = false`) gets smooth, angle-weighted vertex
//!    normals computed in WORLD space ([`normals::smooth_vertex_normals`]);
//! 4. `face_normals = true` drops every vertex normal (the renderer shades with the geometric
//!    normal).
//!
//! # `flip_normals`
//! Mitsuba never flips the stored normals: `Mesh::compute_surface_interaction` and
//! `Mesh::sample_position` (`src/render/mesh.cpp`) negate **both** the geometric normal `si.n`
//! and the shading normal `si.sh_frame.n` at query time. The loaders here therefore keep the
//! normals as in the file, and the renderer must do the same negation whenever
//! [`MeshOptions::flip_normals`] is set: at every intersection and for every emitter position
//! sample on the mesh. (The winding-derived geometric normal and the vertex normals are both
//! negated; the winding itself is unchanged.)
//!
//! # Geometric normal, winding and missing data
//! * The geometric normal is `normalize(cross(p1 − p0, p2 − p0))`: counter-clockwise faces the
//!   viewer. Vertex normals are independent of it and may point the other way (§8).
//! * No `uvs`: Mitsuba's uv is then the barycentric `(b1, b2)` of the hit triangle.
//! * Degenerate (zero-area) triangles are kept, as in Mitsuba; they are never hit and never
//!   produce a NaN normal (a vertex touched only by such triangles gets `(1, 0, 0)`, Mitsuba's
//!   placeholder).

mod attribute;
mod normals;
mod obj;
mod ply;
mod ply_attributes;
mod primitives;
mod serialized;

use glam::{Mat3, Mat4, Vec2, Vec3};
use std::fmt;
use std::path::{Path, PathBuf};

pub use attribute::MeshAttribute;
pub use normals::smooth_vertex_normals;
pub use obj::load_obj;
pub use ply::load_ply;
pub use primitives::{cube, rectangle};
pub use serialized::load_serialized;

/// An indexed triangle mesh in world space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    pub positions: Vec<Vec3>,
    /// Unit normal per vertex; empty = none (shade with the geometric normal).
    pub normals: Vec<Vec3>,
    /// Texture coordinate per vertex; empty = none (uv = barycentric (b1, b2)).
    pub uvs: Vec<Vec2>,
    /// Vertex indices, counter-clockwise = front.
    pub triangles: Vec<[u32; 3]>,
    /// Named vertex/face attributes (PLY only); face attributes have one entry per triangle.
    pub attributes: Vec<MeshAttribute>,
}

impl TriangleMesh {
    /// Total area of all triangles (degenerate ones add 0). Summed in f64 so that meshes with
    /// millions of triangles keep f32 accuracy.
    pub fn surface_area(&self) -> f32 {
        (0..self.triangles.len()).map(|i| self.triangle_area(i) as f64).sum::<f64>() as f32
    }

    /// Area of triangle `i`.
    #[inline]
    pub fn triangle_area(&self, i: usize) -> f32 {
        let [a, b, c] = self.corners(i);
        0.5 * (b - a).cross(c - a).length()
    }

    /// The three world-space corner positions of triangle `i`.
    #[inline]
    pub fn corners(&self, i: usize) -> [Vec3; 3] {
        let [a, b, c] = self.triangles[i];
        [self.positions[a as usize], self.positions[b as usize], self.positions[c as usize]]
    }
}

/// How a mesh is placed and which normals/uvs it keeps (the shape's XML properties).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshOptions {
    pub to_world: Mat4,
    /// Drop all vertex normals and shade with the geometric normal (Mitsuba `face_normals`).
    pub face_normals: bool,
    /// Not applied to the data; see the module documentation: the renderer negates the
    /// geometric and shading normals at query time.
    pub flip_normals: bool,
    /// v ← 1 − v. `None` = the format's default: OBJ `true`, PLY `false` (§8).
    pub flip_tex_coords: Option<bool>,
}

impl Default for MeshOptions {
    fn default() -> Self {
        MeshOptions { to_world: Mat4::IDENTITY, face_normals: false, flip_normals: false, flip_tex_coords: None }
    }
}

impl MeshOptions {
    /// Object → world for points (affine part only, like Mitsuba's `AffineTransform4f`).
    #[inline]
    pub(crate) fn point(&self, p: Vec3) -> Vec3 {
        self.to_world.transform_point3(p)
    }

    /// The matrix that maps normals: the inverse transpose of the linear part. A singular
    /// `to_world` yields non-finite entries, which the loaders report as invalid normals.
    pub(crate) fn normal_matrix(&self) -> Mat3 {
        Mat3::from_mat4(self.to_world).inverse().transpose()
    }
}

/// A mesh file that cannot be loaded: names the file, the line when known, and the problem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshError {
    pub path: PathBuf,
    pub line: Option<usize>,
    pub message: String,
}

impl MeshError {
    pub(crate) fn new(path: &Path, message: impl Into<String>) -> Self {
        MeshError { path: path.to_path_buf(), line: None, message: message.into() }
    }

    pub(crate) fn at(path: &Path, line: usize, message: impl Into<String>) -> Self {
        MeshError { path: path.to_path_buf(), line: Some(line), message: message.into() }
    }
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "{}:{l}: {}", self.path.display(), self.message),
            None => write!(f, "{}: {}", self.path.display(), self.message),
        }
    }
}

impl std::error::Error for MeshError {}

/// Per-vertex data as read from a file (positions already in world space), before the
/// normal policy of §8 is applied by [`finish`].
pub(crate) struct LoadedMesh {
    pub positions: Vec<Vec3>,
    /// World-space unit normal per vertex, `None` where the file gave none. Empty = the file
    /// has no normals at all.
    pub normals: Vec<Option<Vec3>>,
    pub uvs: Vec<Vec2>,
    pub triangles: Vec<[u32; 3]>,
    pub attributes: Vec<MeshAttribute>,
}

/// Applies Mitsuba's normal policy and the checks every loader shares.
///
/// * zero triangles → error (nothing to render; almost always a broken file);
/// * `face_normals` → no vertex normals;
/// * no file normals → smooth angle-weighted normals (`Mesh::recompute_vertex_normals`);
/// * some vertices without a normal (an OBJ face that mixes `v//vn` and `v`; Mitsuba leaves
///   those uninitialised) → they get the smooth normal, so nothing is NaN.
pub(crate) fn finish(path: &Path, m: LoadedMesh, opts: &MeshOptions) -> Result<TriangleMesh, MeshError> {
    if m.triangles.is_empty() {
        return Err(MeshError::new(path, "mesh has no triangles"));
    }
    let normals = if opts.face_normals {
        Vec::new()
    } else if m.normals.iter().all(Option::is_some) && !m.normals.is_empty() {
        m.normals.into_iter().flatten().collect()
    } else {
        let smooth = smooth_vertex_normals(&m.positions, &m.triangles);
        if m.normals.is_empty() {
            smooth
        } else {
            m.normals.into_iter().zip(smooth).map(|(n, s)| n.unwrap_or(s)).collect()
        }
    };
    Ok(TriangleMesh { positions: m.positions, normals, uvs: m.uvs, triangles: m.triangles, attributes: m.attributes })
}

/// `normalize(M · n)` or an error message if the result is not a finite unit vector
/// (zero-length normal in the file, NaN/Inf, or a singular `to_world`). Mitsuba's OBJ loader
/// fails with "mesh contains invalid vertex normal data" in the same cases.
pub(crate) fn world_normal(normal_matrix: &Mat3, n: Vec3) -> Option<Vec3> {
    let w = (*normal_matrix * n).normalize();
    w.is_finite().then_some(w)
}
