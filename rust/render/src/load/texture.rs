//! Reflectance-like parameters: a colour property (`<rgb>`, `<float>`, `<spectrum>`) or a
//! nested/referenced `<texture>`: `bitmap`, `checkerboard`, `rawconstant`, `mesh_attribute` or
//! `volume` with its nested `<volume>` (`gridvolume`, `constvolume`) (docs/renderer-semantics.md
//! §2, §11). Which type builds each plugin name: `bitmap`, `checkerboard`, `mesh_attribute`,
//! `rawconstant` (a constant, `texture/parameter.rs`), the `volume` texture, `gridvolume` and
//! `constvolume` (`texture/volume.rs`) read their own properties in their files under
//! `rust/render/src/texture/` (through [`PluginProps`]). The reads that build a nested texture
//! or volume ([`PluginProps::texture`], [`PluginProps::emission_texture`],
//! [`PluginProps::build_texture`], [`PluginProps::build_volume`]) are here, beside the dispatch.

use super::builder::{Builder, err};
use super::props::{FromProps, PluginProps, Read};
use crate::texture::{BitmapTexture, BoundAttribute, Checkerboard, Texture, Volume, volume};
use glam::Vec3;
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;
use std::sync::Arc;

type Constructor = fn(&mut PluginProps) -> Result<Texture, SceneError>;

plugins! {
    /// Mitsuba 3.9.1's texture plugins matte builds, each with its type.
    pub(super) NAMES, TEXTURES: Constructor = [
        "bitmap" => |p| BitmapTexture::from_props(p).map(|t| Texture::Bitmap(Arc::new(t))),
        "checkerboard" => |p| Checkerboard::from_props(p).map(Texture::Checkerboard),
        "rawconstant" => |p| Texture::raw_constant_from_props(p).map(Texture::Constant),
        // Outside any shape it is only checked.
        "mesh_attribute" => |p| {
            Ok(BoundAttribute::from_props(p)?.map_or(Texture::Constant(Vec3::ZERO), Texture::MeshAttribute))
        },
        "volume" => |p| volume::texture_from_props(p).map(|v| Texture::Volume(Arc::new(v))),
    ];
}

plugins! {
    /// Mitsuba 3.9.1's volume plugins (`src/volumes/`), each with its reader.
    pub(super) VOLUME_NAMES, VOLUMES: fn(&mut PluginProps) -> Result<Volume, SceneError> = [
        "gridvolume" => volume::grid_from_props,
        "constvolume" => volume::constant_from_props,
    ];
}

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

/// A `<texture>` object: one of [`NAMES`].
pub fn build(b: &Builder, obj: &SceneObject) -> Result<Texture, SceneError> {
    let Some(&(_, build)) = TEXTURES.iter().find(|(n, _)| *n == obj.plugin) else {
        let message = format!("unsupported texture type \"{}\" (matte renders: {})", obj.plugin, NAMES.join(", "));
        return Err(err(obj, message));
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

/// A `<volume>` object: one of [`VOLUME_NAMES`] (`src/volumes/`), with the `to_world` of their
/// base class (`Volume::Volume`, `src/render/volume.cpp`: points are taken to local space by
/// its inverse).
pub fn build_volume(b: &Builder, obj: &SceneObject) -> Result<Volume, SceneError> {
    let Some(&(_, build)) = VOLUMES.iter().find(|(n, _)| *n == obj.plugin) else {
        let message =
            format!("unsupported volume type \"{}\" (Mitsuba's are {})", obj.plugin, VOLUME_NAMES.join(" and "));
        return Err(err(obj, message));
    };
    let volume = build(&mut PluginProps::new(b, obj))?;
    obj.check_all_used()?;
    Ok(volume)
}

impl PluginProps<'_> {
    /// A texture: a nested `<texture>` named `name`, else a constant colour property (bounded to
    /// [0, 1] or not, as the plugin reads it), else the harvested default. Absent without a
    /// default: an error (Mitsuba: "property has not been specified").
    pub fn texture(&mut self, name: &str) -> Result<Texture, SceneError> {
        let e = self.entry(name, Read::Texture);
        let default = Self::grey_default(e);
        let obj = self.object();
        if default.is_none() && !obj.properties.contains(name) && !self.has_nested(name) {
            return Err(self.err(format!("missing property \"{name}\"")));
        }
        if let Some(t) = nested(self.builder(), obj, name)? {
            return Ok(t);
        }
        self.colour_value(name, Self::usage(e), default.unwrap_or(Vec3::ZERO)).map(Texture::Constant)
    }

    /// An emitted colour or a nested `<texture>` of that name (not a volume texture, which
    /// matte's emitters cannot look up: their light sampling knows only the uv).
    pub fn emission_texture(&mut self, name: &str) -> Result<Texture, SceneError> {
        match self.child(name) {
            Some(c) if c.tag == "texture" => build_for_emitter(self.builder(), c, name),
            Some(c) => Err(err(c, format!("\"{name}\" must be a colour or a texture"))),
            None => self.emission(name).map(Texture::Constant),
        }
    }

    /// Builds a nested texture object.
    pub fn build_texture(&self, obj: &SceneObject) -> Result<Texture, SceneError> {
        build(self.builder(), obj)
    }

    /// Builds a nested `<volume>` object (`gridvolume`, `constvolume`).
    pub fn build_volume(&self, obj: &SceneObject) -> Result<Volume, SceneError> {
        build_volume(self.builder(), obj)
    }
}
