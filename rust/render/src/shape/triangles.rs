//! World-space triangle meshes: `obj`, `ply`, `rectangle` and `cube` all end up here
//! (Mitsuba `src/render/mesh.cpp`). Geometric normal = normalize((p1−p0)×(p2−p0)), i.e.
//! counter-clockwise faces the viewer; shading normal = interpolated vertex normals when the
//! mesh has them; `flip_normals` negates both at query time (docs/renderer-semantics.md §8).

use super::area_sampling;
use super::interaction::{DirectionSample, SurfaceInteraction};
use super::placement::Placement;
use crate::geometry::{Frame, warp};
use crate::load::props::{PluginProps, one_line};
use glam::{Affine3A, Mat4, Vec2, Vec3};
use matte_scene_file::SceneError;
use matte_scene_file::mesh::{self, MeshOptions, TriangleMesh};

#[derive(Clone, Debug)]
pub struct Triangles {
    pub mesh: TriangleMesh,
    pub flip_normals: bool,
    /// Cumulative triangle areas (for area-proportional sampling), last entry = total area.
    area_cdf: Vec<f32>,
    /// Unit geometric normal per triangle, already flipped with `flip_normals`: computed once
    /// here rather than at every hit and light sample (the cross product and normalisation sat
    /// on the latency chain of every path vertex).
    face_normals: Vec<Vec3>,
    area: f32,
    /// A `rectangle`'s `to_world` and normal (after `flip_normals`): its points are sampled as
    /// Mitsuba's analytic rectangle samples them (`to_world · (2u − 1, 2v − 1, 0)`), not as a
    /// two-triangle mesh.
    rectangle: Option<(Affine3A, Vec3)>,
}

impl Triangles {
    /// `obj`, `ply` and `serialized` (`src/shapes/{obj,ply,serialized}.cpp`, the `Mesh` base
    /// class): `filename`, `face_normals`, `flip_tex_coords` (not `serialized`), `shape_index`
    /// (`serialized` only); the mesh is loaded placed by `at`.
    pub(crate) fn from_file(p: &mut PluginProps, at: Placement) -> Result<Self, SceneError> {
        let plugin = p.object().plugin.as_str();
        let path = p.file("filename")?;
        let opts = MeshOptions {
            to_world: Mat4::from(at.to_world),
            face_normals: p.boolean("face_normals")?,
            flip_normals: at.flip_normals,
            flip_tex_coords: match plugin {
                "serialized" => None,
                _ => p.boolean_opt("flip_tex_coords")?,
            },
        };
        let loaded = match plugin {
            "obj" => mesh::load_obj(&path, &opts),
            "ply" => mesh::load_ply(&path, &opts),
            _ => {
                let index = p.integer("shape_index", 0..=i32::MAX as i64)?;
                mesh::load_serialized(&path, index, &opts)
            }
        };
        let m =
            loaded.map_err(|e| p.prop_err("filename", format!("cannot load mesh: {}", one_line(&e.to_string()))))?;
        Ok(Triangles::new(m, at.flip_normals))
    }

    /// `rectangle` and `cube` placed by `at`: Mitsuba's `Mesh` base class reads `face_normals`
    /// for these too, then ignores it (both are flat per face; `scene_file::mesh::primitives`).
    pub(crate) fn from_primitive(p: &mut PluginProps, at: Placement) -> Result<Self, SceneError> {
        let _ = p.boolean("face_normals")?;
        let opts =
            MeshOptions { to_world: Mat4::from(at.to_world), flip_normals: at.flip_normals, ..MeshOptions::default() };
        Ok(if p.object().plugin == "rectangle" {
            Triangles::rectangle(mesh::rectangle(&opts), at.flip_normals, at.to_world)
        } else {
            Triangles::new(mesh::cube(&opts), at.flip_normals)
        })
    }

    pub fn new(mesh: TriangleMesh, flip_normals: bool) -> Self {
        let mut area_cdf = Vec::with_capacity(mesh.triangles.len());
        let mut face_normals = Vec::with_capacity(mesh.triangles.len());
        let mut acc = 0.0f64;
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            let cross = (b - a).cross(c - a);
            acc += 0.5 * cross.length() as f64;
            area_cdf.push(acc as f32);
            let n = cross.normalize_or_zero();
            face_normals.push(if flip_normals { -n } else { n });
        }
        Triangles { mesh, flip_normals, area: acc as f32, area_cdf, face_normals, rectangle: None }
    }

    /// Mitsuba's `rectangle` with `to_world`: intersected as its two triangles, sampled as the
    /// analytic shape (`src/shapes/rectangle.cpp`, `sample_position`).
    pub fn rectangle(mesh: TriangleMesh, flip_normals: bool, to_world: Affine3A) -> Self {
        let t = Triangles::new(mesh, flip_normals);
        // The rectangle's normal: the inverse transpose of `to_world` applied to +z, flipped.
        let n = t.surface_point(0, Vec2::ZERO).2;
        Triangles { rectangle: Some((to_world, n)), ..t }
    }

    pub fn surface_area(&self) -> f32 {
        self.area
    }

    #[inline]
    pub fn vertices(&self, tri: u32) -> [Vec3; 3] {
        self.mesh.triangles[tri as usize].map(|i| self.mesh.positions[i as usize])
    }

    /// The interaction at barycentrics `(b1, b2)` of triangle `tri`.
    #[inline]
    pub fn interaction(&self, tri: u32, b: Vec2, t: f32, d: Vec3, shape: u32) -> SurfaceInteraction {
        let (p, n, sh_n, uv) = self.surface_point(tri, b);
        let (dp_du, dp_dv) = self.dp_duv(tri, n);
        let sh_frame = Frame::from_normal_dpdu(sh_n, dp_du);
        SurfaceInteraction { t, p, n, sh_frame, uv, shape, wi: sh_frame.to_local(-d), prim: tri, bary: b, dp_du, dp_dv }
    }

    /// Mitsuba's `dp_du`, `dp_dv` (`src/render/mesh.cpp`): p1 − p0 and p2 − p0 without
    /// texture coordinates; with them, the uv-parameterisation derivatives
    /// ((dp0·Δv1 − dp1·Δv0)/det, (dp1·Δu0 − dp0·Δu1)/det), or the
    /// [`coordinate_system`](crate::geometry::orthonormal_frame::coordinate_system) of the face
    /// normal when the uv triangle is degenerate.
    #[inline]
    fn dp_duv(&self, tri: u32, n: Vec3) -> (Vec3, Vec3) {
        let idx = self.mesh.triangles[tri as usize];
        let [p0, p1, p2] = idx.map(|i| self.mesh.positions[i as usize]);
        let (dp0, dp1) = (p1 - p0, p2 - p0);
        if self.mesh.uvs.is_empty() {
            return (dp0, dp1);
        }
        let [uv0, uv1, uv2] = idx.map(|i| self.mesh.uvs[i as usize]);
        let (duv0, duv1) = (uv1 - uv0, uv2 - uv0);
        let det = duv0.x * duv1.y - duv0.y * duv1.x;
        if det == 0.0 {
            return crate::geometry::orthonormal_frame::coordinate_system(n);
        }
        let inv_det = 1.0 / det;
        ((dp0 * duv1.y - dp1 * duv0.y) * inv_det, (dp1 * duv0.x - dp0 * duv1.x) * inv_det)
    }

    /// Position, geometric normal, shading normal and uv at barycentrics `(b1, b2)`.
    #[inline]
    fn surface_point(&self, tri: u32, b: Vec2) -> (Vec3, Vec3, Vec3, Vec2) {
        let idx = self.mesh.triangles[tri as usize];
        let [p0, p1, p2] = idx.map(|i| self.mesh.positions[i as usize]);
        let b0 = 1.0 - b.x - b.y;
        let p = p0 * b0 + p1 * b.x + p2 * b.y;
        let n = self.face_normals[tri as usize];
        let sh_n = if self.mesh.normals.is_empty() {
            n
        } else {
            let [n0, n1, n2] = idx.map(|i| self.mesh.normals[i as usize]);
            let s = (n0 * b0 + n1 * b.x + n2 * b.y).normalize_or_zero();
            if s == Vec3::ZERO {
                n
            } else if self.flip_normals {
                -s
            } else {
                s
            }
        };
        let uv = if self.mesh.uvs.is_empty() {
            b
        } else {
            let [u0, u1, u2] = idx.map(|i| self.mesh.uvs[i as usize]);
            u0 * b0 + u1 * b.x + u2 * b.y
        };
        (p, n, sh_n, uv)
    }

    /// Uniform point on the surface (triangle ∝ area, then uniform inside it); area pdf
    /// `1/A` turned into solid angle at `ref_p` with the shading normal (docs/renderer-semantics.md §8).
    #[inline]
    pub fn sample_direction(&self, ref_p: Vec3, u: Vec2) -> Option<DirectionSample> {
        let (p, sh_n, uv) = self.sample_position(u)?;
        area_sampling::direction_sample(ref_p, p, sh_n, uv, self.area)
    }

    /// A uniform point on the surface: position, shading normal (after `flip_normals`) and
    /// uv; the area density is `1/area`. As Mitsuba maps the sample (which matters with its
    /// `ldsampler`, whose dimensions are not independent): a mesh picks the triangle ∝ area
    /// with `u.y` and reuses it, then warps `u` to the triangle (`Mesh::sample_position`); a
    /// rectangle maps `u` straight onto itself.
    #[inline]
    pub fn sample_position(&self, u: Vec2) -> Option<(Vec3, Vec3, Vec2)> {
        if self.area <= 0.0 {
            return None;
        }
        if let Some((m, n)) = &self.rectangle {
            let p = m.transform_point3(Vec3::new(2.0 * u.x - 1.0, 2.0 * u.y - 1.0, 0.0));
            return Some((p, *n, u));
        }
        let target = u.y * self.area;
        let tri = self.area_cdf.partition_point(|&c| c <= target).min(self.area_cdf.len() - 1);
        let lo = if tri == 0 { 0.0 } else { self.area_cdf[tri - 1] };
        let width = self.area_cdf[tri] - lo;
        let uy = if width > 0.0 { ((target - lo) / width).clamp(0.0, 1.0 - f32::EPSILON / 2.0) } else { 0.0 };
        let b = warp::square_to_uniform_triangle(Vec2::new(u.x, uy));
        let (p, _, sh_n, uv) = self.surface_point(tri as u32, b);
        Some((p, sh_n, uv))
    }

    /// Solid-angle density of [`Self::sample_direction`] for the hit `si` seen from `ref_p`.
    #[inline]
    pub fn pdf_direction(&self, ref_p: Vec3, si: &SurfaceInteraction) -> f32 {
        area_sampling::pdf(ref_p, si.p, si.sh_frame.n, self.area)
    }
}
