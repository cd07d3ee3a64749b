// TEMPORARY stand-in until the meshfilm branch lands.
use glam::{Vec2, Vec3};
#[derive(Clone, Debug, Default)]
pub struct TriangleMesh {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub uvs: Vec<Vec2>,
    pub triangles: Vec<[u32; 3]>,
}
