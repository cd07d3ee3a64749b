//! What the file loaders (`obj.rs`, `ply.rs`, `serialized.rs`) share: the data as read from a
//! file ([`LoadedMesh`]), the normal policy and checks that turn it into a [`TriangleMesh`]
//! ([`finish`]), and a file normal taken to world space ([`world_normal`]).

use super::attribute::MeshAttribute;
use super::error::MeshError;
use super::normals::smooth_vertex_normals;
use super::options::MeshOptions;
use super::triangle_mesh::TriangleMesh;
use glam::{Mat3, Vec2, Vec3};
use std::path::Path;

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
