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
mod error;
mod loaded;
mod normals;
mod obj;
mod options;
mod ply;
mod ply_attributes;
mod primitives;
mod serialized;
mod triangle_mesh;

pub use attribute::MeshAttribute;
pub use error::MeshError;
pub use normals::smooth_vertex_normals;
pub use obj::load_obj;
pub use options::MeshOptions;
pub use ply::load_ply;
pub use primitives::{cube, rectangle};
pub use serialized::load_serialized;
pub use triangle_mesh::TriangleMesh;
