//! [`TriangleMesh`], what every loader and primitive of this module returns: an indexed
//! triangle mesh in world space.

use super::attribute::MeshAttribute;
use glam::{Vec2, Vec3};

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
