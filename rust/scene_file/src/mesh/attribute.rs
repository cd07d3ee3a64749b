//! Per-vertex and per-face mesh attributes (Mitsuba `Mesh::add_attribute`, `src/render/mesh.cpp`):
//! named `vertex_*` or `face_*`, with 1 or 3 floats per entry. PLY files provide them
//! (`src/shapes/ply.h`, `find_other_fields`, and `ply.rs` here); `mesh_attribute` textures
//! read them.

use glam::Vec3;

#[derive(Clone, Debug, PartialEq)]
pub struct MeshAttribute {
    /// `vertex_<prefix>` or `face_<prefix>` (Mitsuba's naming, e.g. `vertex_color`).
    pub name: String,
    /// Floats per entry: 1 or 3 (a PLY colour with alpha gives 4, which nothing can evaluate).
    pub dim: usize,
    /// Per face (one entry per triangle) rather than per vertex.
    pub per_face: bool,
    /// `dim` floats per entry.
    pub values: Vec<f32>,
}

impl MeshAttribute {
    /// Number of entries (vertices or triangles).
    pub fn len(&self) -> usize {
        self.values.len() / self.dim.max(1)
    }

    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Entry `i`: a 1-float attribute in all three channels, else the first three floats.
    #[inline]
    pub fn value(&self, i: usize) -> Vec3 {
        let k = i * self.dim;
        if self.dim == 1 {
            Vec3::splat(self.values[k])
        } else {
            Vec3::new(self.values[k], self.values[k + 1], self.values[k + 2])
        }
    }
}
