//! What every ray-query arrangement returns for a closest hit ([`Hit`]).

use glam::Vec2;

/// A closest hit: distance, shape, primitive (triangle index; 0 for analytic shapes) and
/// barycentrics (meshes only: `(b1, b2)` of vertices 1 and 2).
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub shape: u32,
    pub prim: u32,
    pub bary: Vec2,
}
