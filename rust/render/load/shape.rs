//! `<shape>`: `obj`, `ply`, `serialized`, `rectangle`, `cube` (triangle meshes), `sphere`, `disk`,
//! `cylinder`, each with `to_world`, `flip_normals`, a nested or referenced `<bsdf>` and an
//! optional nested `area` emitter (docs/renderer-semantics.md §8). A shape without a BSDF gets diffuse 0.5,
//! or black diffuse when it emits. `shapegroup` and `instance`: see [`super::instance`].

use super::props::{PluginProps, one_line};
use super::{Builder, ShapeContext, bsdf, emitter, err};
use crate::geometry::Frame;
use crate::shape::{Cylinder, Disk, Geometry, Shape, Sphere, Triangles};
use glam::{Affine3A, Mat3, Mat4, Vec3};
use matte_scene_file::SceneError;
use matte_scene_file::mesh::{self, MeshOptions};
use matte_scene_file::xml::SceneObject;
use std::sync::Arc;

pub fn build(b: &mut Builder, obj: &SceneObject) -> Result<(), SceneError> {
    match obj.plugin.as_str() {
        "shapegroup" => super::instance::check_group(obj),
        "instance" => super::instance::build(b, obj),
        _ => build_placed(b, obj, Affine3A::IDENTITY, false),
    }
}

/// One shape, placed by `outer · to_world` (`outer` is an instance's transform). In a
/// shape group (`in_group`) an area emitter is refused.
pub(super) fn build_placed(
    b: &mut Builder,
    obj: &SceneObject,
    outer: Affine3A,
    in_group: bool,
) -> Result<(), SceneError> {
    let geometry: fn(&mut PluginProps, Affine3A, bool) -> Result<Geometry, SceneError> = match obj.plugin.as_str() {
        "obj" | "ply" | "serialized" => mesh_file,
        "rectangle" | "cube" => mesh_primitive,
        "sphere" => sphere,
        "disk" => disk,
        "cylinder" => cylinder,
        "shapegroup" | "instance" => {
            return Err(err(
                obj,
                "nested instancing is not permitted (a shapegroup cannot contain a shapegroup or an instance)",
            ));
        }
        other => {
            return Err(err(
                obj,
                format!(
                    "unsupported shape type \"{other}\" (matte renders: obj, ply, serialized, rectangle, cube, sphere, disk, cylinder, shapegroup, instance)"
                ),
            ));
        }
    };
    let mut p = PluginProps::new(b, obj);
    let to_world = outer * p.transform("to_world")?;
    let flip_normals = p.boolean("flip_normals")?;
    let geometry = geometry(&mut p, to_world, flip_normals)?;
    check_extent(&p, &geometry)?;
    let shape_index = b.shapes.len() as u32;
    let mut bsdf_index = None;
    let mut emitter_index = None;
    b.shape = Some(match &geometry {
        Geometry::Triangles(t) => ShapeContext {
            is_mesh: true,
            attributes: t.mesh.attributes.iter().cloned().map(Arc::new).collect(),
            triangles: Arc::new(if t.mesh.attributes.is_empty() { Vec::new() } else { t.mesh.triangles.clone() }),
        },
        _ => ShapeContext { is_mesh: false, attributes: Vec::new(), triangles: Arc::new(Vec::new()) },
    });
    let children = attach_children(b, obj, shape_index, in_group, &mut bsdf_index, &mut emitter_index);
    b.shape = None;
    children?;
    let bsdf_index = match bsdf_index {
        Some(i) => i,
        None => bsdf::default_diffuse(b, if emitter_index.is_some() { 0.0 } else { 0.5 }),
    };
    obj.check_all_used()?;
    b.shapes.push(Shape { geometry, bsdf: bsdf_index, emitter: emitter_index, plugin: obj.plugin.clone() });
    Ok(())
}

/// `obj`, `ply` and `serialized` (`src/shapes/{obj,ply,serialized}.cpp`, the `Mesh` base
/// class): `filename`, `face_normals`, `flip_tex_coords` (not `serialized`), `shape_index`
/// (`serialized` only).
fn mesh_file(p: &mut PluginProps, to_world: Affine3A, flip_normals: bool) -> Result<Geometry, SceneError> {
    let plugin = p.object().plugin.as_str();
    let path = p.file("filename")?;
    let opts = MeshOptions {
        to_world: Mat4::from(to_world),
        face_normals: p.boolean("face_normals")?,
        flip_normals,
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
    let m = loaded.map_err(|e| p.prop_err("filename", format!("cannot load mesh: {}", one_line(&e.to_string()))))?;
    Ok(Geometry::Triangles(Triangles::new(m, flip_normals)))
}

/// `rectangle` and `cube`: Mitsuba's `Mesh` base class reads `face_normals` for these too,
/// then ignores it (both are flat per face; scene::mesh::primitives).
fn mesh_primitive(p: &mut PluginProps, to_world: Affine3A, flip_normals: bool) -> Result<Geometry, SceneError> {
    let _ = p.boolean("face_normals")?;
    let opts = MeshOptions { to_world: Mat4::from(to_world), flip_normals, ..MeshOptions::default() };
    Ok(Geometry::Triangles(if p.object().plugin == "rectangle" {
        Triangles::rectangle(mesh::rectangle(&opts), flip_normals, to_world)
    } else {
        Triangles::new(mesh::cube(&opts), flip_normals)
    }))
}

/// `sphere` (`src/shapes/sphere.cpp`): `center` (default the origin) and `radius` (default 1).
fn sphere(p: &mut PluginProps, to_world: Affine3A, flip_normals: bool) -> Result<Geometry, SceneError> {
    let center = p.point("center")?;
    let radius = p.float("radius")? as f32;
    if !(radius.is_finite() && radius > 0.0) {
        return Err(p.prop_err("radius", format!("must be positive, got {radius}")));
    }
    let m = to_world * Affine3A::from_translation(center) * Affine3A::from_scale(Vec3::splat(radius));
    Ok(Geometry::Sphere(Sphere::new(m, flip_normals)))
}

/// `disk` (`src/shapes/disk.cpp`): the unit disk in the xy-plane, placed by `to_world`.
fn disk(_: &mut PluginProps, to_world: Affine3A, flip_normals: bool) -> Result<Geometry, SceneError> {
    Ok(Geometry::Disk(Disk::new(to_world, flip_normals)))
}

/// `cylinder` (`src/shapes/cylinder.cpp`): `p0` (default the origin), `p1` (default +z) and
/// `radius` (default 1), without caps.
fn cylinder(p: &mut PluginProps, to_world: Affine3A, flip_normals: bool) -> Result<Geometry, SceneError> {
    let p0 = p.point_or("p0", Vec3::ZERO)?;
    let p1 = p.point_or("p1", Vec3::Z)?;
    let radius = p.float("radius")? as f32;
    let axis = p1 - p0;
    let length = axis.length();
    if !(radius.is_finite() && radius > 0.0 && length > 0.0 && length.is_finite()) {
        return Err(p.err("needs a positive radius and p0 ≠ p1"));
    }
    // Mitsuba: to_world · T(p0) · to_frame(p1 − p0) · S(r, r, |p1 − p0|).
    let f = Frame::from_normal(axis / length);
    let frame = Affine3A::from_mat3(Mat3::from_cols(f.s, f.t, f.n));
    let m = to_world * Affine3A::from_translation(p0) * frame * Affine3A::from_scale(Vec3::new(radius, radius, length));
    Ok(Geometry::Cylinder(Cylinder::new(m, flip_normals)))
}

/// The shape's geometry must be valid and within ±[`MAX_COORDINATE`].
fn check_extent(p: &PluginProps, geometry: &Geometry) -> Result<(), SceneError> {
    if geometry.surface_area().is_nan() {
        return Err(p.prop_err("to_world", "produces invalid (NaN) geometry"));
    }
    let extent = max_abs_coordinate(geometry);
    if extent.is_nan() || extent > MAX_COORDINATE {
        return Err(p.err(format!("reaches coordinate {extent:e}; matte accepts shapes within ±{MAX_COORDINATE:e}")));
    }
    Ok(())
}

/// The shape's nested or referenced `<bsdf>` and `<emitter>`.
fn attach_children(
    b: &mut Builder,
    obj: &SceneObject,
    shape_index: u32,
    in_group: bool,
    bsdf_index: &mut Option<u32>,
    emitter_index: &mut Option<u32>,
) -> Result<(), SceneError> {
    for child in obj.children.iter() {
        child.mark_used();
        let c = &child.object;
        match c.tag.as_str() {
            "bsdf" => {
                if bsdf_index.is_some() {
                    return Err(err(obj, "has more than one BSDF"));
                }
                *bsdf_index = Some(bsdf::get_or_build(b, c)?);
            }
            "emitter" if in_group => {
                return Err(err(
                    c,
                    "an emitter cannot be attached to a shape inside a shapegroup (instanced emitters are not supported)",
                ));
            }
            "emitter" => {
                if emitter_index.is_some() {
                    return Err(err(obj, "has more than one emitter"));
                }
                *emitter_index = Some(emitter::build_area(b, c, shape_index)?);
            }
            other => return Err(err(c, format!("a <{other}> cannot be nested in a shape"))),
        }
    }
    Ok(())
}

/// Largest world coordinate matte accepts. Mitsuba has no limit, but the BVH builder
/// squares box extents in f32 (overflowing beyond ~1e19), and f32 resolves only ~1e8 units
/// at 1e15 anyway: such a scene cannot be rendered meaningfully.
const MAX_COORDINATE: f32 = 1e15;

/// max |coordinate| over the shape's world-space bounds (NaN if any is NaN).
fn max_abs_coordinate(g: &Geometry) -> f32 {
    let fold = |m: f32, p: Vec3| if p.is_nan() || m.is_nan() { f32::NAN } else { m.max(p.abs().max_element()) };
    match g {
        Geometry::Triangles(t) => t.mesh.positions.iter().fold(0.0, |m, &p| fold(m, p)),
        other => other.analytic_bounds().map_or(f32::NAN, |(lo, hi)| fold(fold(0.0, lo), hi)),
    }
}
