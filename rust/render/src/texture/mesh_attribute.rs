//! Mitsuba's `mesh_attribute` texture (`src/textures/mesh_attribute.cpp`, `Mesh::eval_attribute*`
//! in `src/render/mesh.cpp`, v3.9.1), bound to one mesh's attribute.
//!
//! * A `vertex_*` attribute is interpolated with the hit's barycentrics, a `face_*` one is
//!   the hit triangle's value; both times `scale` (default 1).
//! * `eval` (colours): a 1-channel attribute in all three channels, a 3-channel one as RGB.
//! * `eval_1` (scalar parameters): the 1-channel value. A 3-channel attribute has no scalar
//!   value: Mitsuba's scalar variants throw, its JIT variants return 0, and matte returns 0.
//!
//! docs/renderer-semantics.md §11 (mesh attributes).

use crate::load::props::PluginProps;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;
use matte_scene_file::mesh::MeshAttribute;
use std::sync::Arc;

/// One mesh's attribute as a texture.
#[derive(Clone, Debug)]
pub struct BoundAttribute {
    pub attribute: Arc<MeshAttribute>,
    /// The mesh's triangles (vertex indices), for interpolating vertex attributes.
    pub triangles: Arc<Vec<[u32; 3]>>,
    pub scale: f32,
}

impl BoundAttribute {
    /// The attribute's value at triangle `prim`, barycentrics `(b1, b2)`, before `scale`.
    #[inline]
    fn raw(&self, prim: u32, bary: Vec2) -> Vec3 {
        let a = &self.attribute;
        if a.per_face {
            return a.value(prim as usize);
        }
        let [i0, i1, i2] = self.triangles[prim as usize];
        let b0 = 1.0 - bary.x - bary.y;
        a.value(i0 as usize) * b0 + a.value(i1 as usize) * bary.x + a.value(i2 as usize) * bary.y
    }

    #[inline]
    pub fn eval(&self, prim: u32, bary: Vec2) -> Vec3 {
        self.raw(prim, bary) * self.scale
    }

    #[inline]
    pub fn eval_1(&self, prim: u32, bary: Vec2) -> f32 {
        if self.attribute.dim == 1 { self.raw(prim, bary).x * self.scale } else { 0.0 }
    }

    /// Mean of the stored values' channel means. (Mitsuba's `mesh_attribute` has no `mean()`:
    /// the base class throws; matte uses it only for plastics' lobe-selection weight.)
    pub fn mean(&self) -> f32 {
        let a = &self.attribute;
        let n = a.len().max(1);
        let sum: f32 = (0..a.len()).map(|i| a.value(i)).map(|v| (v.x + v.y + v.z) / 3.0).sum();
        sum / n as f32 * self.scale
    }
}

impl BoundAttribute {
    /// Reads a `mesh_attribute`: `name` (must contain
    /// `vertex_` or `face_`) and `scale` (default 1), bound to the attribute of that name of the
    /// shape being built. A definition outside any shape (a top-level `<texture id>`) is only
    /// checked (`None`); every shape that uses it binds its own copy.
    pub(crate) fn from_props(p: &mut PluginProps) -> Result<Option<Self>, SceneError> {
        let name = p.required_string("name")?;
        if !name.contains("vertex_") && !name.contains("face_") {
            return Err(
                p.prop_err("name", format!("must start with either \"vertex_\" or \"face_\" but was \"{name}\""))
            );
        }
        let scale = p.float("scale")? as f32;
        p.object().check_all_used()?;
        let b = p.builder();
        b.shape_dependent.set(true);
        let Some(shape) = &b.shape else { return Ok(None) };
        if !shape.is_mesh {
            return Err(p.err("a mesh attribute needs a mesh shape (obj, ply, rectangle, cube)"));
        }
        let Some(attribute) = shape.attributes.iter().find(|a| a.name == name) else {
            let names: Vec<&str> = shape.attributes.iter().map(|a| a.name.as_str()).collect();
            let has = if names.is_empty() { "none".to_string() } else { names.join(", ") };
            return Err(p.prop_err("name", format!("the shape has no attribute \"{name}\" (it has: {has})")));
        };
        if attribute.dim != 1 && attribute.dim != 3 {
            let message = format!("attribute \"{name}\" has {} channels; only 1 or 3 can be evaluated", attribute.dim);
            return Err(p.prop_err("name", message));
        }
        let (attribute, triangles) = (attribute.clone(), shape.triangles.clone());
        Ok(Some(BoundAttribute { attribute, triangles, scale }))
    }
}
