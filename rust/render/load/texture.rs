//! Reflectance-like parameters: a colour property (`<rgb>`, `<float>`, `<spectrum>`) or a
//! nested/referenced `<texture>`: `bitmap`, `checkerboard`, `rawconstant`, `mesh_attribute` or
//! `volume` with its nested `<volume>` (`gridvolume`, `constvolume`) (docs/renderer-semantics.md
//! §2, §11).

use super::{Builder, err, values};
use crate::texture::Texture;
use crate::texture::{
    BitmapFilter, BitmapOptions, BitmapTexture, BoundAttribute, Checkerboard, GridFilter, GridVolume, Volume,
    VolumeData, VolumeGrid, WrapMode,
};
use glam::{Affine2, Affine3A, Mat2, Vec2, Vec3};
use matte_scene_file::SceneError;
use matte_scene_file::xml::{ColorUse, SceneObject, Value};
use std::sync::Arc;

/// The parameter `name` of `obj` as a texture: nested texture child of that name, else a
/// colour property, else `default`.
pub fn get(b: &Builder, obj: &SceneObject, name: &str, usage: ColorUse, default: Vec3) -> Result<Texture, SceneError> {
    if let Some(child) = obj.child(name) {
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
        return Ok(t);
    }
    Ok(Texture::Constant(values::color(obj, name, usage, default)?))
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
    match obj.plugin.as_str() {
        "bitmap" => build_bitmap(b, obj),
        "checkerboard" => checkerboard(b, obj),
        "rawconstant" => rawconstant(obj),
        "mesh_attribute" => mesh_attribute(b, obj),
        "volume" => volume_texture(b, obj),
        other => Err(err(
            obj,
            format!(
                "unsupported texture type \"{other}\" (matte renders: bitmap, checkerboard, rawconstant, mesh_attribute, \
                 volume)"
            ),
        )),
    }
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
fn volume_texture(b: &Builder, obj: &SceneObject) -> Result<Texture, SceneError> {
    if let Some(p) = obj.properties.iter().find(|p| p.name == "volume") {
        return Err(values::prop_err(
            obj,
            "volume",
            format!(
                "has the wrong type (expected a nested <volume>, found {}); write <volume name=\"volume\" \
                 type=\"gridvolume\"> or type=\"constvolume\"",
                p.value.type_name()
            ),
        ));
    }
    if obj.child("volume").is_none() {
        // Another nested object is reported as such (unused), before the missing one.
        obj.check_all_used()?;
    }
    let child = obj.child("volume").ok_or_else(|| {
        err(
            obj,
            "missing property \"volume\" (a nested <volume name=\"volume\" type=\"gridvolume\"> or \"constvolume\")",
        )
    })?;
    if child.object.tag != "volume" {
        return Err(err(
            &child.object,
            format!("\"volume\" must be a <volume> (gridvolume, constvolume), not a <{}>", child.object.tag),
        ));
    }
    let volume = build_volume(b, &child.object)?;
    obj.check_all_used()?;
    Ok(Texture::Volume(Arc::new(volume)))
}

/// A `<volume>` object: `gridvolume` or `constvolume` (`src/volumes/`), with the `to_world` of
/// their base class (`Volume::Volume`, `src/render/volume.cpp`: points are taken to local space
/// by its inverse).
pub fn build_volume(b: &Builder, obj: &SceneObject) -> Result<Volume, SceneError> {
    let to_world = values::transform(obj, "to_world")?;
    match obj.plugin.as_str() {
        "gridvolume" => {
            let to_local = to_world.inverse();
            if !(to_world.matrix3.determinant() != 0.0 && to_local.is_finite()) {
                return Err(values::prop_err(
                    obj,
                    "to_world",
                    "must be invertible (points are looked up through its inverse)",
                ));
            }
            gridvolume(b, obj, to_local)
        }
        // Its value does not depend on the point: to_world is read and has no effect.
        "constvolume" => constvolume(b, obj),
        other => {
            Err(err(obj, format!("unsupported volume type \"{other}\" (Mitsuba's are gridvolume and constvolume)")))
        }
    }
}

/// Mitsuba's `gridvolume` (`src/volumes/grid.cpp`): `filename` (a `.vol` file), `filter_type`
/// (trilinear, nearest), `wrap_mode` (clamp, repeat, mirror) and `use_grid_bbox`, with
/// Mitsuba's messages. `raw`, `accel` and `max_value` are accepted without effect
/// (`load/no_effect.rs`).
fn gridvolume(b: &Builder, obj: &SceneObject, to_local: Affine3A) -> Result<Volume, SceneError> {
    let filter = match values::string(obj, "filter_type", "trilinear")?.as_str() {
        "trilinear" => GridFilter::Trilinear,
        "nearest" => GridFilter::Nearest,
        other => {
            return Err(values::prop_err(
                obj,
                "filter_type",
                format!("Invalid filter type \"{other}\", must be one of: \"nearest\" or \"trilinear\"!"),
            ));
        }
    };
    let word = values::string(obj, "wrap_mode", "clamp")?;
    let wrap = WrapMode::parse(&word).ok_or_else(|| {
        let message = format!("Invalid wrap mode \"{word}\", must be one of: \"repeat\", \"mirror\", or \"clamp\"!");
        values::prop_err(obj, "wrap_mode", message)
    })?;
    let use_grid_bbox = values::boolean(obj, "use_grid_bbox", false)?;
    let filename = obj.properties.string("filename")?.ok_or_else(|| err(obj, "missing property \"filename\""))?;
    obj.check_all_used()?;
    let path = b.resolve(&filename);
    let file_err =
        |msg: &str| values::prop_err(obj, "filename", format!("\"{}\": {}", path.display(), values::one_line(msg)));
    let grid = VolumeGrid::read(&path).map_err(|e| file_err(&e))?;
    let to_local = if use_grid_bbox {
        // `VolumeGrid::bbox_transform`: scale(1/extents)·translate(−min), after to_local.
        let extents = grid.bbox_max - grid.bbox_min;
        if !(extents.min_element() > 0.0) {
            return Err(file_err(&format!(
                "use_grid_bbox needs a bounding box with positive extents, the file's is {} to {}",
                grid.bbox_min, grid.bbox_max
            )));
        }
        Affine3A::from_scale(extents.recip()) * Affine3A::from_translation(-grid.bbox_min) * to_local
    } else {
        to_local
    };
    let data = GridVolume::new(&grid, filter, wrap).map_err(|e| file_err(&e))?;
    Ok(Volume { to_local, data: VolumeData::Grid(data) })
}

/// Mitsuba's `constvolume` (`src/volumes/const.cpp`): `value`, an unbounded colour or a texture
/// (default 1), looked up at uv = (0, 0) whatever the point.
fn constvolume(b: &Builder, obj: &SceneObject) -> Result<Volume, SceneError> {
    let value = get(b, obj, "value", ColorUse::Unbounded, Vec3::ONE)?;
    if matches!(value, Texture::MeshAttribute(_) | Texture::Volume(_)) {
        let c = obj.child("value").expect("a nested texture");
        return Err(err(
            &c.object,
            "constvolume looks its value up without a surface point: a mesh_attribute or volume texture is not supported",
        ));
    }
    obj.check_all_used()?;
    Ok(Volume { to_local: Affine3A::IDENTITY, data: VolumeData::Constant(value) })
}

/// Mitsuba's `checkerboard` (`src/textures/checkerboard.cpp`): `color0` and `color1` (colours,
/// defaults 0.4 and 0.2) and `to_uv`; the lookup is [`Checkerboard`]'s. Textured colours are
/// not supported.
fn checkerboard(b: &Builder, obj: &SceneObject) -> Result<Texture, SceneError> {
    let colour = |name: &str, default: f32| -> Result<Vec3, SceneError> {
        match get(b, obj, name, ColorUse::Bounded, Vec3::splat(default))? {
            Texture::Constant(c) => Ok(c),
            _ => Err(err(obj, format!("\"{name}\" must be a colour (a textured {name} is not supported by matte)"))),
        }
    };
    let (color0, color1) = (colour("color0", 0.4)?, colour("color1", 0.2)?);
    let to_uv = to_uv(obj)?;
    obj.check_all_used()?;
    Ok(Texture::Checkerboard(Checkerboard { color0, color1, to_uv }))
}

/// Mitsuba's `mesh_attribute` (`src/textures/mesh_attribute.cpp`): `name` (must contain
/// `vertex_` or `face_`) and `scale` (default 1), bound to the attribute of that name of the
/// shape being built. A definition outside any shape (a top-level `<texture id>`) is only
/// checked here; every shape that uses it binds its own copy.
fn mesh_attribute(b: &Builder, obj: &SceneObject) -> Result<Texture, SceneError> {
    let name = obj.properties.string("name")?.ok_or_else(|| err(obj, "missing property \"name\""))?;
    if !name.contains("vertex_") && !name.contains("face_") {
        return Err(values::prop_err(
            obj,
            "name",
            format!("must start with either \"vertex_\" or \"face_\" but was \"{name}\""),
        ));
    }
    let scale = values::float(obj, "scale", 1.0)? as f32;
    obj.check_all_used()?;
    b.shape_dependent.set(true);
    let Some(shape) = &b.shape else { return Ok(Texture::Constant(Vec3::ZERO)) };
    if !shape.is_mesh {
        return Err(err(obj, "a mesh attribute needs a mesh shape (obj, ply, rectangle, cube)"));
    }
    let Some(attribute) = shape.attributes.iter().find(|a| a.name == name) else {
        let names: Vec<&str> = shape.attributes.iter().map(|a| a.name.as_str()).collect();
        return Err(values::prop_err(
            obj,
            "name",
            format!(
                "the shape has no attribute \"{name}\" (it has: {})",
                if names.is_empty() { "none".to_string() } else { names.join(", ") }
            ),
        ));
    };
    if attribute.dim != 1 && attribute.dim != 3 {
        return Err(values::prop_err(
            obj,
            "name",
            format!("attribute \"{name}\" has {} channels; only 1 or 3 can be evaluated", attribute.dim),
        ));
    }
    Ok(Texture::MeshAttribute(BoundAttribute {
        attribute: attribute.clone(),
        triangles: shape.triangles.clone(),
        scale,
    }))
}

/// Mitsuba's `rawconstant` (`src/spectra/rawconstant.cpp`): `value`, a `<float>` (all three
/// channels) or a `<vector>`, used as is (no colour conversion, no range check).
fn rawconstant(obj: &SceneObject) -> Result<Texture, SceneError> {
    let value = match obj.properties.iter().find(|p| p.name == "value").map(|p| &p.value) {
        None => return Err(err(obj, "missing required parameter \"value\" (a float or a 3-D vector)")),
        Some(Value::Vector(_) | Value::Point(_)) => obj.properties.vector("value")?.unwrap_or_default().as_vec3(),
        Some(Value::Float(_) | Value::Integer(_)) => {
            Vec3::splat(obj.properties.float("value")?.unwrap_or_default() as f32)
        }
        Some(other) => {
            return Err(values::prop_err(
                obj,
                "value",
                format!("has the wrong type (expected float or vector, found {})", other.type_name()),
            ));
        }
    };
    if !value.is_finite() {
        return Err(values::prop_err(obj, "value", "must be finite"));
    }
    obj.check_all_used()?;
    Ok(Texture::Constant(value))
}

/// `to_uv` as a 2-D affine map: the upper-left 2×2 block and the translation column of the
/// 4×4 transform (Mitsuba's `Properties::get<AffineTransform3f>`).
fn to_uv(obj: &SceneObject) -> Result<Affine2, SceneError> {
    Ok(match obj.properties.transform("to_uv")? {
        None => Affine2::IDENTITY,
        Some(m) => {
            let a = Mat2::from_cols(
                Vec2::new(m.x_axis.x as f32, m.x_axis.y as f32),
                Vec2::new(m.y_axis.x as f32, m.y_axis.y as f32),
            );
            Affine2::from_mat2_translation(a, Vec2::new(m.w_axis.x as f32, m.w_axis.y as f32))
        }
    })
}

fn build_bitmap(b: &Builder, obj: &SceneObject) -> Result<Texture, SceneError> {
    let filename = obj.properties.string("filename")?.ok_or_else(|| err(obj, "missing property \"filename\""))?;
    let filter = match values::string(obj, "filter_type", "bilinear")?.as_str() {
        "bilinear" => BitmapFilter::Bilinear,
        "nearest" => BitmapFilter::Nearest,
        other => {
            return Err(values::prop_err(obj, "filter_type", format!("must be bilinear or nearest, got \"{other}\"")));
        }
    };
    let word = values::string(obj, "wrap_mode", "repeat")?;
    let wrap = WrapMode::parse(&word).ok_or_else(|| {
        values::prop_err(obj, "wrap_mode", format!("must be repeat, mirror or clamp, got \"{word}\""))
    })?;
    let raw = values::boolean(obj, "raw", false)?;
    let to_uv = to_uv(obj)?;
    let _ = values::string(obj, "format", "variant")?;
    obj.check_all_used()?;
    let path = b.resolve(&filename);
    let tex = BitmapTexture::load(&path, &BitmapOptions { filter, wrap, raw, to_uv })
        .map_err(|e| values::prop_err(obj, "filename", format!("\"{}\": {}", path.display(), values::one_line(&e))))?;
    Ok(Texture::Bitmap(Arc::new(tex)))
}
