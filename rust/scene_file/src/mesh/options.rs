//! [`MeshOptions`]: a mesh shape's XML properties that say how its data is placed and which
//! normals and uvs it keeps, read by every loader and primitive.

use glam::{Mat3, Mat4, Vec3};

/// How a mesh is placed and which normals/uvs it keeps (the shape's XML properties).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshOptions {
    pub to_world: Mat4,
    /// Drop all vertex normals and shade with the geometric normal (Mitsuba `face_normals`).
    pub face_normals: bool,
    /// Not applied to the data; see the [`mesh`](crate::mesh) module documentation: the
    /// renderer negates the geometric and shading normals at query time.
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
