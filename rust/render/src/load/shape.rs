//! `<shape>`: which type builds each plugin name. `obj`, `ply`, `serialized`, `rectangle` and
//! `cube` (triangle meshes), `sphere`, `disk` and `cylinder` read their own properties
//! (`from_props` in their files under `rust/render/src/shape/`, through [`PluginProps`], after the
//! `Shape` base class's `to_world` and `flip_normals`, [`Placement`]); the loader attaches a
//! nested or referenced `<bsdf>` and an optional nested `area` emitter
//! (docs/renderer-semantics.md §8) and checks the extent. A shape without a BSDF gets diffuse
//! 0.5, or black diffuse when it emits. `shapegroup` and `instance` are declared here with the
//! family and built on these shapes by `load/instance.rs` (the loader's walk dispatches to it).

use super::builder::{Builder, ShapeContext, err};
use super::props::PluginProps;
use super::{bsdf, emitter};
use crate::shape::{Cylinder, Disk, Geometry, Placement, Shape, Sphere, Triangles};
use glam::{Affine3A, Vec3};
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;
use std::sync::Arc;

/// How a shape plugin is built.
pub(super) enum How {
    /// Its geometry, placed by the `Shape` base class's transform ([`Placement`]).
    Placed(fn(&mut PluginProps, Placement) -> Result<Geometry, SceneError>),
    /// `shapegroup`: a group of shapes for instances (`load/instance.rs`).
    Group,
    /// `instance`: a group placed once more (`load/instance.rs`).
    Instance,
}

plugins! {
    /// Mitsuba 3.9.1's shape plugins matte builds, each with how.
    pub(super) NAMES, SHAPES: How = [
        "obj" => How::Placed(|p, at| Triangles::from_file(p, at).map(Geometry::Triangles)),
        "ply" => How::Placed(|p, at| Triangles::from_file(p, at).map(Geometry::Triangles)),
        "serialized" => How::Placed(|p, at| Triangles::from_file(p, at).map(Geometry::Triangles)),
        "rectangle" => How::Placed(|p, at| Triangles::from_primitive(p, at).map(Geometry::Triangles)),
        "cube" => How::Placed(|p, at| Triangles::from_primitive(p, at).map(Geometry::Triangles)),
        "sphere" => How::Placed(|p, at| Sphere::from_props(p, at).map(Geometry::Sphere)),
        "disk" => How::Placed(|p, at| Disk::from_props(p, at).map(Geometry::Disk)),
        "cylinder" => How::Placed(|p, at| Cylinder::from_props(p, at).map(Geometry::Cylinder)),
        "shapegroup" => How::Group,
        "instance" => How::Instance,
    ];
}

/// How the shape `obj` is built; `None` for a plugin matte does not render.
pub(super) fn how(obj: &SceneObject) -> Option<&'static How> {
    SHAPES.iter().find(|(n, _)| *n == obj.plugin).map(|(_, how)| how)
}

/// One shape, placed by `outer · to_world` (`outer` is an instance's transform). In a
/// shape group (`in_group`) an area emitter is refused.
pub(super) fn build_placed(
    b: &mut Builder,
    obj: &SceneObject,
    outer: Affine3A,
    in_group: bool,
) -> Result<(), SceneError> {
    let geometry = match how(obj) {
        Some(How::Placed(geometry)) => *geometry,
        Some(How::Group | How::Instance) => {
            return Err(err(
                obj,
                "nested instancing is not permitted (a shapegroup cannot contain a shapegroup or an instance)",
            ));
        }
        None => {
            let message = format!("unsupported shape type \"{}\" (matte renders: {})", obj.plugin, NAMES.join(", "));
            return Err(err(obj, message));
        }
    };
    let mut p = PluginProps::new(b, obj);
    let at = Placement::from_props(&mut p, outer)?;
    let geometry = geometry(&mut p, at)?;
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
