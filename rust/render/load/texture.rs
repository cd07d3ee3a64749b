//! Reflectance-like parameters: a colour property (`<rgb>`, `<float>`, `<spectrum>`) or a
//! nested/referenced `<texture type="bitmap">` (docs/renderer-semantics.md §2, §11) or `checkerboard`.

use super::{Builder, err, values};
use crate::texture::Texture;
use crate::texture::{BitmapFilter, BitmapOptions, BitmapTexture, BoundAttribute, Checkerboard, WrapMode};
use glam::{Affine2, Mat2, Vec2, Vec3};
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
        return build(b, &child.object);
    }
    Ok(Texture::Constant(values::color(obj, name, usage, default)?))
}

/// A `<texture>` object: `bitmap` or `checkerboard`.
pub fn build(b: &Builder, obj: &SceneObject) -> Result<Texture, SceneError> {
    match obj.plugin.as_str() {
        "bitmap" => build_bitmap(b, obj),
        "checkerboard" => checkerboard(b, obj),
        "rawconstant" => rawconstant(obj),
        "mesh_attribute" => mesh_attribute(b, obj),
        other => Err(err(
            obj,
            format!(
                "unsupported texture type \"{other}\" (matte renders: bitmap, checkerboard, rawconstant, mesh_attribute)"
            ),
        )),
    }
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
    let wrap = match values::string(obj, "wrap_mode", "repeat")?.as_str() {
        "repeat" => WrapMode::Repeat,
        "mirror" => WrapMode::Mirror,
        "clamp" => WrapMode::Clamp,
        other => {
            return Err(values::prop_err(
                obj,
                "wrap_mode",
                format!("must be repeat, mirror or clamp, got \"{other}\""),
            ));
        }
    };
    let raw = values::boolean(obj, "raw", false)?;
    let to_uv = to_uv(obj)?;
    let _ = values::string(obj, "format", "variant")?;
    obj.check_all_used()?;
    let path = b.resolve(&filename);
    let tex = BitmapTexture::load(&path, &BitmapOptions { filter, wrap, raw, to_uv })
        .map_err(|e| values::prop_err(obj, "filename", format!("\"{}\": {}", path.display(), values::one_line(&e))))?;
    Ok(Texture::Bitmap(Arc::new(tex)))
}
