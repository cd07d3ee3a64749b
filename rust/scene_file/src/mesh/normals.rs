//! Smooth vertex normals for meshes whose file has none: Mitsuba's
//! `Mesh::recompute_vertex_normals` (`src/render/mesh.cpp`), after Thürmer & Wüthrich,
//! "Computing Vertex Normals from Polygonal Facets" (JGT 1998): each face adds its unit normal
//! weighted by the face's angle at the vertex. Done in f32 on WORLD-space positions, like
//! Mitsuba, so a non-uniformly scaled mesh gets the normals of its scaled shape.

use glam::Vec3;
use std::f32::consts::PI;

/// Angle-weighted unit normal per vertex. Zero-area faces are skipped; a vertex that only
/// touches such faces (or whose contributions cancel) gets `(1, 0, 0)`, Mitsuba's placeholder,
/// so the result never contains NaN or Inf. Indices must be in range.
pub fn smooth_vertex_normals(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut acc = vec![Vec3::ZERO; positions.len()];
    for tri in triangles {
        let v = tri.map(|i| positions[i as usize]);
        let n = (v[1] - v[0]).cross(v[2] - v[0]);
        let len_sqr = n.length_squared();
        if !(len_sqr > 0.0 && len_sqr.is_finite()) {
            continue;
        }
        let n = n / len_sqr.sqrt();
        for j in 0..3 {
            let e1 = (v[(j + 1) % 3] - v[j]).normalize();
            let e2 = (v[(j + 2) % 3] - v[j]).normalize();
            let angle = unit_angle(e1, e2);
            if angle.is_finite() {
                acc[tri[j] as usize] += n * angle;
            }
        }
    }
    acc.into_iter()
        .map(|n| {
            let len = n.length();
            if len > 0.0 && len.is_finite() { n / len } else { Vec3::X }
        })
        .collect()
}

/// Angle between two unit vectors, accurate also for nearly (anti)parallel ones
/// (the `2·asin(|a ∓ b|/2)` form Mitsuba's `unit_angle` uses instead of `acos(dot)`).
#[inline]
fn unit_angle(a: Vec3, b: Vec3) -> f32 {
    if a.dot(b) < 0.0 {
        PI - 2.0 * (0.5 * (a + b).length()).min(1.0).asin()
    } else {
        2.0 * (0.5 * (a - b).length()).min(1.0).asin()
    }
}
