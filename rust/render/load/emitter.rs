//! `<emitter>`: `area` (nested in a shape), `point`, `spot`, `directional`, `constant`
//! (docs/renderer-semantics.md §9; emissive colours follow §2: `<spectrum value=v>` is not white), and
//! `envmap` (`src/emitters/envmap.cpp`: filename, scale, to_world, mis_compensation).

use super::{Builder, err, values};
use crate::camera::x_half_tan;
use crate::emitter::{self, Emitter, EnvMap};
use crate::texture::Texture;
use crate::texture::{BitmapOptions, BitmapTexture};
use glam::Vec3;
use matte_scene_file::SceneError;
use matte_scene_file::xml::{ColorUse, SceneObject};
use std::sync::Arc;

fn weight(obj: &SceneObject) -> Result<f32, SceneError> {
    let w = values::float(obj, "sampling_weight", 1.0)?;
    if !(w.is_finite() && w >= 0.0) {
        return Err(values::prop_err(obj, "sampling_weight", format!("must be ≥ 0, got {w}")));
    }
    Ok(w as f32)
}

fn emissive(obj: &SceneObject, name: &str) -> Result<Vec3, SceneError> {
    if obj.child(name).is_some() {
        return Err(err(obj, format!("a texture for \"{name}\" is not supported by matte render")));
    }
    let v = values::color(obj, name, ColorUse::Emissive, Vec3::ONE)?;
    if !v.is_finite() {
        return Err(values::prop_err(obj, name, "must be finite"));
    }
    Ok(v)
}

fn push(b: &mut Builder, e: Emitter, w: f32) -> u32 {
    b.emitters.push(e);
    b.sampling_weights.push(w);
    (b.emitters.len() - 1) as u32
}

/// An `area` emitter nested in shape `shape`.
pub fn build_area(b: &mut Builder, obj: &SceneObject, shape: u32) -> Result<u32, SceneError> {
    if obj.plugin != "area" {
        return Err(err(obj, "only an \"area\" emitter can be nested in a shape"));
    }
    if obj.properties.contains("to_world") {
        return Err(values::prop_err(obj, "to_world", "is not allowed on an area emitter (it follows its shape)"));
    }
    let radiance = match obj.child("radiance") {
        Some(c) if c.object.tag == "texture" => {
            let t = super::texture::build_for_emitter(b, &c.object, "radiance")?;
            if matches!(t, Texture::MeshAttribute(_)) {
                return Err(err(
                    &c.object,
                    "a mesh attribute as an emitter's radiance is not supported by matte render",
                ));
            }
            t
        }
        _ => Texture::Constant(emissive(obj, "radiance")?),
    };
    let w = weight(obj)?;
    obj.check_all_used()?;
    b.area_emitters.insert(obj as *const SceneObject);
    Ok(push(b, Emitter::Area { shape, radiance }, w))
}

/// A top-level emitter.
pub fn build_standalone(b: &mut Builder, obj: &SceneObject) -> Result<(), SceneError> {
    let w = weight(obj)?;
    let e = match obj.plugin.as_str() {
        "point" => {
            let intensity = emissive(obj, "intensity")?;
            let position = match (obj.properties.point("position")?, obj.properties.contains("to_world")) {
                (Some(_), true) => return Err(err(obj, "give either position or to_world, not both")),
                (Some(p), false) => p.as_vec3(),
                (None, _) => values::transform(obj, "to_world")?.translation.into(),
            };
            Emitter::Point { position, intensity }
        }
        "spot" => {
            let intensity = emissive(obj, "intensity")?;
            let cutoff = values::float(obj, "cutoff_angle", 20.0)?;
            let beam = values::float(obj, "beam_width", cutoff * 0.75)?;
            if !(cutoff > 0.0 && cutoff <= 180.0 && beam > 0.0 && beam <= cutoff) {
                return Err(err(obj, format!("needs 0 < beam_width ({beam}) ≤ cutoff_angle ({cutoff}) ≤ 180")));
            }
            // `texture` (`get_texture`, default 1) must vary spatially when given.
            let texture = match obj.child("texture") {
                None => None,
                Some(c) if c.object.tag == "texture" => {
                    Some(super::texture::build_for_emitter(b, &c.object, "texture")?)
                }
                Some(c) => return Err(err(&c.object, "\"texture\" must be a texture (e.g. bitmap)")),
            };
            if obj.properties.contains("texture") {
                return Err(values::prop_err(
                    obj,
                    "texture",
                    "must be spatially varying (e.g. bitmap type), as in Mitsuba",
                ));
            }
            emitter::spot(values::transform(obj, "to_world")?, intensity, cutoff as f32, beam as f32, texture)
        }
        "directional" => {
            let irradiance = emissive(obj, "irradiance")?;
            let direction = match (obj.properties.vector("direction")?, obj.properties.contains("to_world")) {
                (Some(_), true) => return Err(err(obj, "give either direction or to_world, not both")),
                (Some(d), false) => d.as_vec3(),
                (None, _) => values::transform(obj, "to_world")?.transform_vector3(Vec3::Z),
            };
            let direction = direction.normalize_or_zero();
            if direction == Vec3::ZERO || !direction.is_finite() {
                return Err(err(obj, "direction must be a non-zero vector"));
            }
            Emitter::Directional { direction, irradiance }
        }
        "constant" => {
            // Every Mitsuba emitter reads `to_world` (src/render/endpoint.cpp); a uniform
            // environment is invariant under it, so it is validated and ignored.
            values::transform(obj, "to_world")?;
            Emitter::Constant { radiance: emissive(obj, "radiance")? }
        }
        "envmap" => envmap(b, obj)?,
        "projector" => projector(b, obj)?,
        "area" => return Err(err(obj, "an area emitter must be nested in a shape")),
        other => {
            return Err(err(
                obj,
                format!(
                    "unsupported emitter type \"{other}\" (matte renders: area, point, spot, projector, directional, constant, envmap)"
                ),
            ));
        }
    };
    obj.check_all_used()?;
    push(b, e, w);
    Ok(())
}

/// `scale` (finite, default 1) and an invertible `to_world`, as `envmap` and `projector` take them.
fn scale_and_to_world(obj: &SceneObject) -> Result<(f64, glam::Affine3A), SceneError> {
    let scale = values::float(obj, "scale", 1.0)?;
    if !scale.is_finite() {
        return Err(values::prop_err(obj, "scale", "must be finite"));
    }
    let to_world = values::transform(obj, "to_world")?;
    if to_world.matrix3.determinant() == 0.0 {
        return Err(values::prop_err(obj, "to_world", "must be invertible"));
    }
    Ok((scale, to_world))
}

/// `envmap`: the image file (found through the scene's search folders), `scale` (default 1),
/// `to_world`, `mis_compensation` (default false). Mitsuba's `bitmap` property (an in-memory
/// image) has no XML form.
fn envmap(b: &Builder, obj: &SceneObject) -> Result<Emitter, SceneError> {
    let filename = obj.properties.string("filename")?.ok_or_else(|| err(obj, "missing property \"filename\""))?;
    let (scale, to_world) = scale_and_to_world(obj)?;
    let mis_compensation = values::boolean(obj, "mis_compensation", false)?;
    let path = b.resolve(&filename);
    let tex = BitmapTexture::load(&path, &BitmapOptions::default())
        .map_err(|e| values::prop_err(obj, "filename", format!("\"{}\": {}", path.display(), values::one_line(&e))))?;
    let [w, h] = tex.resolution();
    let map = EnvMap::new(w as usize, h as usize, tex.texels().to_vec(), scale as f32, to_world, mis_compensation)
        .map_err(|e| values::prop_err(obj, "filename", format!("\"{}\": {e}", path.display())))?;
    Ok(Emitter::EnvMap(Arc::new(map)))
}

/// `projector` (`src/emitters/projector.cpp`): `irradiance` (an emissive colour or texture,
/// default 1), `scale` (default 1), `to_world`, and the field of view as for `perspective`
/// (`fov` + `fov_axis`, or `focal_length`, default 50mm) over the texture's aspect ratio.
fn projector(b: &Builder, obj: &SceneObject) -> Result<Emitter, SceneError> {
    let (irradiance, aspect) = match obj.child("irradiance") {
        Some(c) if c.object.tag == "texture" => {
            let t = super::texture::build_for_emitter(b, &c.object, "irradiance")?;
            let aspect = match &t {
                Texture::Bitmap(bm) => {
                    let [w, h] = bm.resolution();
                    w as f64 / h as f64
                }
                _ => 1.0,
            };
            (t, aspect)
        }
        Some(c) => return Err(err(&c.object, "\"irradiance\" must be a colour or a texture")),
        None => (Texture::Constant(emissive(obj, "irradiance")?), 1.0),
    };
    let (scale, to_world) = scale_and_to_world(obj)?;
    let (fov_deg, axis) = super::sensor::field_of_view(obj)?;
    let tan_half = x_half_tan(fov_deg, axis, aspect) as f32;
    Ok(Emitter::Projector {
        to_world,
        to_local: to_world.inverse(),
        irradiance,
        tan_half,
        aspect: aspect as f32,
        scale: scale as f32,
    })
}
