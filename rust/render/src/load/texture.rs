//! Reflectance-like parameters: a colour property (`<rgb>`, `<float>`, `<spectrum>`) or a
//! nested/referenced `<texture>`: `bitmap`, `checkerboard`, `rawconstant`, `mesh_attribute` or
//! `volume` with its nested `<volume>` (`gridvolume`, `constvolume`) (docs/renderer-semantics.md
//! §2, §11). Which type builds each plugin name: `bitmap`, `checkerboard`, `mesh_attribute`,
//! `rawconstant` (a constant, `texture/parameter.rs`), the `volume` texture, `gridvolume` and
//! `constvolume` (`texture/volume.rs`) read their own properties in their files under
//! `rust/render/src/texture/` (through [`PluginProps`]).

use super::props::{FromProps, PluginProps};
use super::{Builder, err};
use crate::texture::{BitmapTexture, BoundAttribute, Checkerboard, Texture, Volume, volume};
use glam::Vec3;
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;
use std::sync::Arc;

/// The parameter `name` of `obj` given as a nested (or referenced) `<texture>`, built; `None`
/// when no nested object has that name (the caller reads a colour property instead).
pub fn nested(b: &Builder, obj: &SceneObject, name: &str) -> Result<Option<Texture>, SceneError> {
    let Some(child) = obj.child(name) else { return Ok(None) };
    if obj.properties.contains(name) {
        return Err(err(obj, format!("\"{name}\" is given both as a property and as a texture")));
    }
    if child.object.tag != "texture" {
        return Err(err(&child.object, format!("\"{name}\" must be a texture or a colour")));
    }
    let t = build(b, &child.object)?;
    if matches!(t, Texture::Volume(_)) && calls_mean(obj, name) {
        return Err(err(
            &child.object,
            format!(
                "{} \"{}\" asks its \"{name}\" for its mean, which Mitsuba's volume texture does not have \
                 (Texture::mean(): not implemented!)",
                obj.tag, obj.plugin
            ),
        ));
    }
    Ok(Some(t))
}

/// Whether Mitsuba asks the texture given as parameter `name` of `obj` for its `mean()` when it
/// builds `obj`: `plastic` and `roughplastic` for their lobe-selection weight, matte's plugin for
/// a textured numeric parameter of its models (a number standing for the texture).
fn calls_mean(obj: &SceneObject, name: &str) -> bool {
    obj.tag == "bsdf"
        && match obj.plugin.as_str() {
            "plastic" | "roughplastic" => name == "diffuse_reflectance",
            p => matte_brdf::BSDF_TYPES.contains(&p) && name != "reflectance",
        }
}

/// A `<texture>` object: `bitmap`, `checkerboard`, `rawconstant`, `mesh_attribute` or `volume`.
pub fn build(b: &Builder, obj: &SceneObject) -> Result<Texture, SceneError> {
    let build: fn(&mut PluginProps) -> Result<Texture, SceneError> = match obj.plugin.as_str() {
        "bitmap" => |p| BitmapTexture::from_props(p).map(|t| Texture::Bitmap(Arc::new(t))),
        "checkerboard" => |p| Checkerboard::from_props(p).map(Texture::Checkerboard),
        "rawconstant" => |p| Texture::raw_constant_from_props(p).map(Texture::Constant),
        // Outside any shape it is only checked.
        "mesh_attribute" => {
            |p| Ok(BoundAttribute::from_props(p)?.map_or(Texture::Constant(Vec3::ZERO), Texture::MeshAttribute))
        }
        "volume" => |p| volume::texture_from_props(p).map(|v| Texture::Volume(Arc::new(v))),
        other => {
            return Err(err(
                obj,
                format!(
                    "unsupported texture type \"{other}\" (matte renders: bitmap, checkerboard, rawconstant, \
                     mesh_attribute, volume)"
                ),
            ));
        }
    };
    let texture = build(&mut PluginProps::new(b, obj))?;
    obj.check_all_used()?;
    Ok(texture)
}

/// A `<texture>` given to an emitter (`what`: its parameter): as [`build`], except a volume
/// texture, which matte's emitters cannot look up (their light sampling knows only the uv).
pub fn build_for_emitter(b: &Builder, obj: &SceneObject, what: &str) -> Result<Texture, SceneError> {
    let t = build(b, obj)?;
    if matches!(t, Texture::Volume(_)) {
        return Err(err(obj, format!("a volume texture as an emitter's {what} is not supported by matte render")));
    }
    Ok(t)
}

/// A `<volume>` object: `gridvolume` or `constvolume` (`src/volumes/`), with the `to_world` of
/// their base class (`Volume::Volume`, `src/render/volume.cpp`: points are taken to local space
/// by its inverse).
pub fn build_volume(b: &Builder, obj: &SceneObject) -> Result<Volume, SceneError> {
    let build: fn(&mut PluginProps) -> Result<Volume, SceneError> = match obj.plugin.as_str() {
        "gridvolume" => volume::grid_from_props,
        "constvolume" => volume::constant_from_props,
        other => {
            return Err(err(
                obj,
                format!("unsupported volume type \"{other}\" (Mitsuba's are gridvolume and constvolume)"),
            ));
        }
    };
    let volume = build(&mut PluginProps::new(b, obj))?;
    obj.check_all_used()?;
    Ok(volume)
}
