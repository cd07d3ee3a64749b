//! Reflectance-like parameters: a colour property (`<rgb>`, `<float>`, `<spectrum>`) or a
//! nested/referenced `<texture>`: `bitmap`, `checkerboard`, `rawconstant`, `mesh_attribute` or
//! `volume` with its nested `<volume>` (`gridvolume`, `constvolume`) (docs/renderer-semantics.md
//! §2, §11).

use super::props::PluginProps;
use super::{Builder, err};
use crate::texture::Texture;
use crate::texture::{
    BitmapFilter, BitmapOptions, BitmapTexture, BoundAttribute, Checkerboard, GridFilter, GridVolume, Volume,
    VolumeData, VolumeGrid, WrapMode,
};
use glam::{Affine3A, Vec3};
use matte_scene_file::SceneError;
use matte_scene_file::xml::{SceneObject, Value};
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
        "bitmap" => bitmap,
        "checkerboard" => checkerboard,
        "rawconstant" => rawconstant,
        "mesh_attribute" => mesh_attribute,
        "volume" => volume_texture,
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

/// Mitsuba's `volume` texture (`src/textures/volume.cpp`): one property, `volume`, a nested or
/// referenced `<volume>` (`gridvolume`, `constvolume`), looked up at the world-space hit point.
/// Mitsuba reads it as an object (a number there is "wrong type (expected object, got float)"),
/// and without one it loads and crashes when evaluated: matte requires it.
fn volume_texture(p: &mut PluginProps) -> Result<Texture, SceneError> {
    if let Some(v) = p.raw("volume") {
        let found = v.type_name();
        return Err(p.prop_err(
            "volume",
            format!(
                "has the wrong type (expected a nested <volume>, found {found}); write <volume name=\"volume\" \
                 type=\"gridvolume\"> or type=\"constvolume\""
            ),
        ));
    }
    let Some(child) = p.child("volume") else {
        // Another nested object is reported as such (unused), before the missing one.
        p.object().check_all_used()?;
        return Err(p.err(
            "missing property \"volume\" (a nested <volume name=\"volume\" type=\"gridvolume\"> or \"constvolume\")",
        ));
    };
    if child.tag != "volume" {
        return Err(err(
            child,
            format!("\"volume\" must be a <volume> (gridvolume, constvolume), not a <{}>", child.tag),
        ));
    }
    Ok(Texture::Volume(Arc::new(build_volume(p.builder(), child)?)))
}

/// A `<volume>` object: `gridvolume` or `constvolume` (`src/volumes/`), with the `to_world` of
/// their base class (`Volume::Volume`, `src/render/volume.cpp`: points are taken to local space
/// by its inverse).
pub fn build_volume(b: &Builder, obj: &SceneObject) -> Result<Volume, SceneError> {
    let build: fn(&mut PluginProps) -> Result<Volume, SceneError> = match obj.plugin.as_str() {
        "gridvolume" => gridvolume,
        "constvolume" => constvolume,
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

/// Mitsuba's `gridvolume` (`src/volumes/grid.cpp`): `to_world` (invertible: points are looked
/// up through its inverse), `filename` (a `.vol` file), `filter_type` (trilinear, nearest),
/// `wrap_mode` (clamp, repeat, mirror) and `use_grid_bbox`, with Mitsuba's messages. `raw`,
/// `accel` and `max_value` are accepted without effect (`load/no_effect.rs`).
fn gridvolume(p: &mut PluginProps) -> Result<Volume, SceneError> {
    let to_world = p.transform("to_world")?;
    let to_local = to_world.inverse();
    if !(to_world.matrix3.determinant() != 0.0 && to_local.is_finite()) {
        return Err(p.prop_err("to_world", "must be invertible (points are looked up through its inverse)"));
    }
    let filter = match p.string("filter_type")?.as_str() {
        "trilinear" => GridFilter::Trilinear,
        "nearest" => GridFilter::Nearest,
        other => {
            let message = format!("Invalid filter type \"{other}\", must be one of: \"nearest\" or \"trilinear\"!");
            return Err(p.prop_err("filter_type", message));
        }
    };
    let word = p.string("wrap_mode")?;
    let wrap = WrapMode::parse(&word).ok_or_else(|| {
        let message = format!("Invalid wrap mode \"{word}\", must be one of: \"repeat\", \"mirror\", or \"clamp\"!");
        p.prop_err("wrap_mode", message)
    })?;
    let use_grid_bbox = p.boolean("use_grid_bbox")?;
    let path = p.file("filename")?;
    p.object().check_all_used()?;
    let grid = VolumeGrid::read(&path).map_err(|e| p.file_err("filename", &path, &e))?;
    let to_local = if use_grid_bbox { grid_bbox(p, &path, &grid)? * to_local } else { to_local };
    let data = GridVolume::new(&grid, filter, wrap).map_err(|e| p.file_err("filename", &path, &e))?;
    Ok(Volume { to_local, data: VolumeData::Grid(data) })
}

/// `VolumeGrid::bbox_transform`: scale(1/extents)·translate(−min), applied after to_local.
fn grid_bbox(p: &PluginProps, path: &std::path::Path, grid: &VolumeGrid) -> Result<Affine3A, SceneError> {
    let extents = grid.bbox_max - grid.bbox_min;
    if !(extents.min_element() > 0.0) {
        let message = format!(
            "use_grid_bbox needs a bounding box with positive extents, the file's is {} to {}",
            grid.bbox_min, grid.bbox_max
        );
        return Err(p.file_err("filename", path, &message));
    }
    Ok(Affine3A::from_scale(extents.recip()) * Affine3A::from_translation(-grid.bbox_min))
}

/// Mitsuba's `constvolume` (`src/volumes/const.cpp`): `value`, an unbounded colour or a texture
/// (default 1), looked up at uv = (0, 0) whatever the point. Its value does not depend on the
/// point: `to_world` is read and has no effect.
fn constvolume(p: &mut PluginProps) -> Result<Volume, SceneError> {
    p.transform("to_world")?;
    let value = p.texture("value")?;
    if matches!(value, Texture::MeshAttribute(_) | Texture::Volume(_)) {
        let c = p.child("value").expect("a nested texture");
        return Err(err(
            c,
            "constvolume looks its value up without a surface point: a mesh_attribute or volume texture is not supported",
        ));
    }
    Ok(Volume { to_local: Affine3A::IDENTITY, data: VolumeData::Constant(value) })
}

/// Mitsuba's `checkerboard` (`src/textures/checkerboard.cpp`): `color0` and `color1` (colours,
/// defaults 0.4 and 0.2) and `to_uv`; the lookup is [`Checkerboard`]'s. Textured colours are
/// not supported.
fn checkerboard(p: &mut PluginProps) -> Result<Texture, SceneError> {
    let mut colour = |name: &str| -> Result<Vec3, SceneError> {
        match p.texture(name)? {
            Texture::Constant(c) => Ok(c),
            _ => Err(p.err(format!("\"{name}\" must be a colour (a textured {name} is not supported by matte)"))),
        }
    };
    let (color0, color1) = (colour("color0")?, colour("color1")?);
    let to_uv = p.uv_transform("to_uv")?;
    Ok(Texture::Checkerboard(Checkerboard { color0, color1, to_uv }))
}

/// Mitsuba's `mesh_attribute` (`src/textures/mesh_attribute.cpp`): `name` (must contain
/// `vertex_` or `face_`) and `scale` (default 1), bound to the attribute of that name of the
/// shape being built. A definition outside any shape (a top-level `<texture id>`) is only
/// checked here; every shape that uses it binds its own copy.
fn mesh_attribute(p: &mut PluginProps) -> Result<Texture, SceneError> {
    let name = p.required_string("name")?;
    if !name.contains("vertex_") && !name.contains("face_") {
        return Err(p.prop_err("name", format!("must start with either \"vertex_\" or \"face_\" but was \"{name}\"")));
    }
    let scale = p.float("scale")? as f32;
    p.object().check_all_used()?;
    let b = p.builder();
    b.shape_dependent.set(true);
    let Some(shape) = &b.shape else { return Ok(Texture::Constant(Vec3::ZERO)) };
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
    Ok(Texture::MeshAttribute(BoundAttribute { attribute, triangles, scale }))
}

/// Mitsuba's `rawconstant` (`src/spectra/rawconstant.cpp`): `value`, a `<float>` (all three
/// channels) or a `<vector>`, used as is (no colour conversion, no range check).
fn rawconstant(p: &mut PluginProps) -> Result<Texture, SceneError> {
    let value = match p.raw("value") {
        None => return Err(p.err("missing required parameter \"value\" (a float or a 3-D vector)")),
        Some(Value::Vector(_) | Value::Point(_)) => p.point_opt("value")?.unwrap_or_default(),
        Some(Value::Float(_) | Value::Integer(_)) => Vec3::splat(p.float_opt("value")?.unwrap_or_default() as f32),
        Some(other) => {
            let message = format!("has the wrong type (expected float or vector, found {})", other.type_name());
            return Err(p.prop_err("value", message));
        }
    };
    if !value.is_finite() {
        return Err(p.prop_err("value", "must be finite"));
    }
    Ok(Texture::Constant(value))
}

/// Mitsuba's `bitmap` (`src/textures/bitmap.cpp`): `filename`, `filter_type` (bilinear,
/// nearest), `wrap_mode`, `raw`, `to_uv`; `format` is read and has no effect (matte keeps RGB).
fn bitmap(p: &mut PluginProps) -> Result<Texture, SceneError> {
    let path = p.file("filename")?;
    let filter = match p.string("filter_type")?.as_str() {
        "bilinear" => BitmapFilter::Bilinear,
        "nearest" => BitmapFilter::Nearest,
        other => {
            return Err(p.prop_err("filter_type", format!("must be bilinear or nearest, got \"{other}\"")));
        }
    };
    let word = p.string("wrap_mode")?;
    let wrap = WrapMode::parse(&word)
        .ok_or_else(|| p.prop_err("wrap_mode", format!("must be repeat, mirror or clamp, got \"{word}\"")))?;
    let raw = p.boolean("raw")?;
    let to_uv = p.uv_transform("to_uv")?;
    let _ = p.string("format")?;
    p.object().check_all_used()?;
    let tex = BitmapTexture::load(&path, &BitmapOptions { filter, wrap, raw, to_uv })
        .map_err(|e| p.file_err("filename", &path, &e))?;
    Ok(Texture::Bitmap(Arc::new(tex)))
}
