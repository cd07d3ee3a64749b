//! `<bsdf>`: Mitsuba's `diffuse`, `twosided`, `dielectric`, `thindielectric`, `roughdielectric`,
//! `conductor`, `roughconductor`, `plastic`, `roughplastic`, `normalmap`, `bumpmap`, `mask`, `blendbsdf`, `principled`,
//! `principledthin`, `null`, `tabulated_brdf` (a table file, `docs/microgeometry.md`) and matte's `lambert`, `oren_nayar`, `eon`, `wolff`, `ginneken`,
//! `roughdiffuse` (parameters validated by the kernels' own parser, the same one the Mitsuba
//! plugin uses).

use super::bsdf_params::{MAX_MAGNITUDE, constant, ior, microfacet, optional_constant, relative_ior, too_large};
use super::{Builder, bsdf_principled, err, texture, values};
use crate::brdf::{BSDF_TYPES, ParamValue, Params};
use crate::render::bsdf::{
    Blend, Bsdf, BumpMap, Conductor, Dielectric, Mask, NormalMap, Plastic, RoughConductor, RoughDielectric, RoughLobe,
    RoughPlastic, TabulatedBrdf, TexturedMatte, TexturedRoughness, ThinDielectric, conductor_material,
};
use crate::render::texture::Texture;
use crate::scene_file::SceneError;
use crate::scene_file::xml::{ColorUse, SceneObject, Value};
use glam::Vec3;

/// The BSDF index for this XML object, building it the first time it is seen.
/// A BSDF that depends on its shape (a `mesh_attribute` texture, a `bumpmap`) is built again
/// for every shape.
pub fn get_or_build(b: &mut Builder, obj: &SceneObject) -> Result<u32, SceneError> {
    let key = obj as *const SceneObject;
    if let Some(&i) = b.bsdf_index.get(&key) {
        return Ok(i);
    }
    let outer = b.shape_dependent.replace(false);
    let bsdf = build(b, obj);
    let dependent = b.shape_dependent.replace(outer);
    let bsdf = bsdf?;
    b.bsdfs.push(bsdf);
    let i = (b.bsdfs.len() - 1) as u32;
    if dependent {
        b.shape_dependent_bsdfs.insert(key);
    } else {
        b.bsdf_index.insert(key, i);
    }
    Ok(i)
}

/// A constant-colour diffuse BSDF (Mitsuba's default for shapes without one).
pub fn default_diffuse(b: &mut Builder, reflectance: f32) -> u32 {
    b.bsdfs.push(Bsdf::Diffuse { reflectance: Texture::Constant(Vec3::splat(reflectance)) });
    (b.bsdfs.len() - 1) as u32
}

fn build(b: &mut Builder, obj: &SceneObject) -> Result<Bsdf, SceneError> {
    let bsdf = match obj.plugin.as_str() {
        "diffuse" => {
            Bsdf::Diffuse { reflectance: texture::get(b, obj, "reflectance", ColorUse::Bounded, Vec3::splat(0.5))? }
        }
        kind if BSDF_TYPES.contains(&kind) => {
            let reflectance = texture::get(b, obj, "reflectance", ColorUse::Bounded, Vec3::splat(0.5))?;
            let mut params = Params::new();
            for p in obj.properties.iter().filter(|p| p.name != "reflectance") {
                // Numbers are range-checked by the kernels' `Params`, as in every front end.
                let value = match &p.value {
                    Value::Float(x) => ParamValue::Number(*x),
                    Value::Integer(i) => ParamValue::Number(*i as f64),
                    Value::String(s) => ParamValue::Text(s.clone()),
                    Value::Boolean(v) => ParamValue::Text(v.to_string()),
                    other => {
                        return Err(values::prop_err(
                            obj,
                            &p.name,
                            format!("must be a number or a string, not {}", other.type_name()),
                        ));
                    }
                };
                p.used.set(true);
                params.push(&p.name, value);
            }
            // Numeric parameters given as nested textures (sigma, roughness, alpha, int_ior, …):
            // the model is validated with each texture's mean, then evaluated per hit.
            let mut textured: Vec<(String, Texture)> = Vec::new();
            for child in obj.children.iter().filter(|c| c.name.as_deref().is_some_and(|n| n != "reflectance")) {
                let name = child.name.clone().unwrap_or_default();
                if !numeric_parameter(kind, &name) {
                    return Err(values::prop_err(
                        obj,
                        &name,
                        "is not a numeric parameter of this model, so it cannot be a texture",
                    ));
                }
                textured.push((name.clone(), texture::get_scalar(b, obj, &name, Vec3::ZERO)?));
            }
            // A textured parameter stands for a number when the model is built: its mean,
            // clamped into the per-lane range (any texture is accepted; values clamp per hit).
            let number = |n: &str| match obj.properties.get(n).map(|p| &p.value) {
                Some(Value::Float(x)) => Some(*x),
                Some(Value::Integer(i)) => Some(*i as f64),
                Some(Value::String(s)) => crate::brdf::params::lookup_ior(s),
                _ => None,
            };
            for (name, tex) in &textured {
                let v = crate::brdf::lane::textured_placeholder(kind, name, tex.mean() as f64, number);
                params.push(name, ParamValue::Number(v));
            }
            let model = crate::brdf::DiffuseModel::from_params(kind, params)
                .map_err(|e| values::prop_err(obj, &e.param, e.message))?;
            if textured.is_empty() {
                Bsdf::Matte { model, reflectance }
            } else {
                textured_matte(obj, model, reflectance, textured)?
            }
        }
        "tabulated_brdf" => {
            let reflectance = texture::get(b, obj, "reflectance", ColorUse::Bounded, Vec3::splat(0.5))?;
            let filename =
                obj.properties.string("filename")?.ok_or_else(|| err(obj, "missing property \"filename\""))?;
            let path = b.resolve(&filename);
            let table = crate::brdf::tabulated::BrdfTable::read(&path)
                .map_err(|e| values::prop_err(obj, "filename", values::one_line(&e)))?;
            Bsdf::Tabulated(TabulatedBrdf { table: std::sync::Arc::new(table), reflectance })
        }
        "twosided" => {
            let nested: Vec<_> = obj.children_with_tag("bsdf").map(|c| c.object.clone()).collect();
            let (front, back) = match nested.as_slice() {
                [one] => {
                    let f = build(b, one)?;
                    (f.clone(), f)
                }
                [f, bk] => (build(b, f)?, build(b, bk)?),
                _ => return Err(err(obj, format!("needs one or two nested BSDFs, found {}", nested.len()))),
            };
            // Mitsuba's `allow_transmission` (default false) lifts the check below.
            let allow_transmission = values::boolean(obj, "allow_transmission", false)?;
            for side in [&front, &back] {
                let transmissive = is_transmissive(side);
                if transmissive && !allow_transmission {
                    return Err(err(
                        obj,
                        "a twosided BSDF cannot wrap a transmissive BSDF unless allow_transmission is true (as in Mitsuba)",
                    ));
                }
            }
            Bsdf::TwoSided { front: Box::new(front), back: Box::new(back) }
        }
        "dielectric" => {
            let int_ior = ior(obj, "int_ior", 1.5046)?;
            let ext_ior = ior(obj, "ext_ior", 1.000277)?;
            let r = constant(obj, "specular_reflectance")?;
            let t = constant(obj, "specular_transmittance")?;
            Bsdf::Dielectric(Dielectric::new(int_ior, ext_ior, r, t).map_err(|e| err(obj, e))?)
        }
        "conductor" => {
            let (eta, k) = conductor_ior(obj)?;
            Bsdf::Conductor(Conductor::new(eta, k, constant(obj, "specular_reflectance")?).map_err(|e| err(obj, e))?)
        }
        "roughconductor" => {
            let mf = microfacet(Some(b), obj, true)?;
            let (eta, k) = conductor_ior(obj)?;
            let r = constant(obj, "specular_reflectance")?;
            let lobe = RoughConductor::new(mf.kind, mf.alpha_u, mf.alpha_v, mf.sample_visible, eta, k, r)
                .map_err(|e| err(obj, e))?;
            match mf.alpha_tex {
                None => Bsdf::RoughConductor(lobe),
                Some((alpha_u, alpha_v)) => Bsdf::TexturedRoughness(Box::new(TexturedRoughness {
                    alpha_u,
                    alpha_v,
                    lobe: RoughLobe::Conductor(lobe),
                })),
            }
        }
        "thindielectric" => {
            let eta = ior(obj, "int_ior", 1.5046)? / ior(obj, "ext_ior", 1.000277)?;
            let r = constant(obj, "specular_reflectance")?;
            let t = constant(obj, "specular_transmittance")?;
            Bsdf::ThinDielectric(ThinDielectric::new(eta, r, t).map_err(|e| err(obj, e))?)
        }
        "roughdielectric" => {
            let mf = microfacet(Some(b), obj, true)?;
            let eta = relative_ior(obj, 1.5046)?;
            let r = constant(obj, "specular_reflectance")?;
            let t = constant(obj, "specular_transmittance")?;
            let lobe = RoughDielectric::new(mf.kind, mf.alpha_u, mf.alpha_v, mf.sample_visible, eta, r, t)
                .map_err(|e| err(obj, e))?;
            match mf.alpha_tex {
                None => Bsdf::RoughDielectric(lobe),
                Some((alpha_u, alpha_v)) => Bsdf::TexturedRoughness(Box::new(TexturedRoughness {
                    alpha_u,
                    alpha_v,
                    lobe: RoughLobe::Dielectric(lobe),
                })),
            }
        }
        "normalmap" => {
            let nested: Vec<_> = obj.children_with_tag("bsdf").map(|c| c.object.clone()).collect();
            let [inner] = nested.as_slice() else {
                return Err(err(obj, format!("needs exactly one nested BSDF, found {}", nested.len())));
            };
            if obj.child("normalmap").is_none() && !obj.properties.contains("normalmap") {
                return Err(err(obj, "missing the \"normalmap\" texture"));
            }
            let normals = texture::get(b, obj, "normalmap", ColorUse::Unbounded, Vec3::new(0.5, 0.5, 1.0))?;
            let flip_invalid_normals = values::boolean(obj, "flip_invalid_normals", true)?;
            let use_shadowing_function = values::boolean(obj, "use_shadowing_function", true)?;
            Bsdf::NormalMap(NormalMap {
                normals,
                nested: Box::new(build(b, inner)?),
                flip_invalid_normals,
                use_shadowing_function,
            })
        }
        // `src/bsdfs/null.cpp`: no scattering, rays pass straight through (`Bsdf::Null`).
        "null" => Bsdf::Null,
        "mask" => {
            let nested: Vec<_> = obj.children_with_tag("bsdf").map(|c| c.object.clone()).collect();
            let [inner] = nested.as_slice() else {
                return Err(err(obj, format!("needs exactly one nested BSDF, found {}", nested.len())));
            };
            let opacity = texture::get(b, obj, "opacity", ColorUse::Bounded, Vec3::splat(0.5))?;
            Bsdf::Mask(Mask { opacity, nested: Box::new(build(b, inner)?) })
        }
        "bumpmap" => {
            let nested: Vec<_> = obj.children_with_tag("bsdf").map(|c| c.object.clone()).collect();
            let [inner] = nested.as_slice() else {
                return Err(err(obj, format!("needs exactly one nested BSDF, found {}", nested.len())));
            };
            let textures: Vec<_> = obj.children_with_tag("texture").map(|c| c.object.clone()).collect();
            let [height] = textures.as_slice() else {
                return Err(err(
                    obj,
                    format!("needs exactly one nested texture (the height map), found {}", textures.len()),
                ));
            };
            // The texture may have any name (Mitsuba takes the one texture child).
            if height.plugin != "bitmap" {
                return Err(err(
                    height,
                    "a bumpmap needs a bitmap height texture (Mitsuba's other textures have no gradient)",
                ));
            }
            let height = texture::build(b, height)?;
            b.shape_dependent.set(true);
            if b.shape.as_ref().is_some_and(|s| !s.is_mesh) {
                return Err(err(
                    obj,
                    "bumpmap is supported on meshes only (obj, ply, rectangle, cube): matte's analytic shapes have no ∂p/∂u, ∂p/∂v",
                ));
            }
            let scale = values::float(obj, "scale", 1.0)? as f32;
            let flip_invalid_normals = values::boolean(obj, "flip_invalid_normals", true)?;
            let use_shadowing_function = values::boolean(obj, "use_shadowing_function", true)?;
            Bsdf::BumpMap(Box::new(BumpMap {
                height,
                nested: Box::new(build(b, inner)?),
                scale,
                flip_invalid_normals,
                use_shadowing_function,
            }))
        }
        "blendbsdf" => {
            let nested: Vec<_> = obj.children_with_tag("bsdf").map(|c| c.object.clone()).collect();
            let [first, second] = nested.as_slice() else {
                return Err(err(obj, format!("needs exactly two nested BSDFs, found {}", nested.len())));
            };
            if obj.child("weight").is_none() && !obj.properties.contains("weight") {
                return Err(err(obj, "missing the blend \"weight\" (a float or a texture)"));
            }
            let weight = texture::get(b, obj, "weight", ColorUse::Bounded, Vec3::ZERO)?;
            Bsdf::Blend(Box::new(Blend {
                weight,
                first: Box::new(build(b, first)?),
                second: Box::new(build(b, second)?),
            }))
        }
        "principled" => Bsdf::Principled(Box::new(bsdf_principled::principled(b, obj)?)),
        "principledthin" => Bsdf::PrincipledThin(Box::new(bsdf_principled::principled_thin(b, obj)?)),
        "plastic" => {
            let eta = ior(obj, "int_ior", 1.49)? / ior(obj, "ext_ior", 1.000277)?;
            let diffuse = texture::get(b, obj, "diffuse_reflectance", ColorUse::Bounded, Vec3::splat(0.5))?;
            let specular = optional_constant(obj, "specular_reflectance")?;
            let nonlinear = values::boolean(obj, "nonlinear", false)?;
            Bsdf::Plastic(Box::new(Plastic::new(eta, diffuse, specular, nonlinear).map_err(|e| err(obj, e))?))
        }
        "roughplastic" => {
            let mf = microfacet(None, obj, false)?;
            let eta = relative_ior(obj, 1.49)?;
            let diffuse = texture::get(b, obj, "diffuse_reflectance", ColorUse::Bounded, Vec3::splat(0.5))?;
            let specular = optional_constant(obj, "specular_reflectance")?;
            let nonlinear = values::boolean(obj, "nonlinear", false)?;
            Bsdf::RoughPlastic(Box::new(
                RoughPlastic::new(mf.kind, mf.alpha_u, mf.sample_visible, eta, diffuse, specular, nonlinear)
                    .map_err(|e| err(obj, e))?,
            ))
        }
        other => {
            return Err(err(
                obj,
                format!(
                    "unsupported bsdf type \"{other}\" (matte renders: diffuse, twosided, dielectric, thindielectric, roughdielectric, \
                     conductor, roughconductor, plastic, roughplastic, normalmap, bumpmap, mask, blendbsdf, principled, principledthin, tabulated_brdf, {})",
                    BSDF_TYPES.join(", ")
                ),
            ));
        }
    };
    obj.check_all_used()?;
    Ok(bsdf)
}

/// Whether Mitsuba's flags of the BSDF include a transmission (`twosided` refuses those).
fn is_transmissive(bsdf: &Bsdf) -> bool {
    match bsdf {
        // principledthin always declares a diffuse transmission component.
        Bsdf::Dielectric(_) | Bsdf::RoughDielectric(_) | Bsdf::ThinDielectric(_) | Bsdf::PrincipledThin(_) => true,
        // mask's null component and `null` itself are a transmission (`BSDFFlags::Null`).
        Bsdf::Mask(_) | Bsdf::Null => true,
        Bsdf::Principled(p) => p.spec_trans.is_some(),
        Bsdf::TexturedRoughness(t) => matches!(t.lobe, RoughLobe::Dielectric(_)),
        Bsdf::Blend(b) => is_transmissive(&b.first) || is_transmissive(&b.second),
        Bsdf::NormalMap(n) => is_transmissive(&n.nested),
        Bsdf::BumpMap(m) => is_transmissive(&m.nested),
        _ => false,
    }
}

/// Whether `name` is a numeric parameter of matte's model `kind` (those a texture may give).
fn numeric_parameter(kind: &str, name: &str) -> bool {
    crate::brdf::lane::numeric_parameter_names(kind).contains(&name)
}

/// A matte model with textured numeric parameters (`TexturedMatte`); every other numeric
/// parameter becomes a constant texture of its value.
fn textured_matte(
    obj: &SceneObject,
    model: crate::brdf::DiffuseModel,
    reflectance: Texture,
    mut textured: Vec<(String, Texture)>,
) -> Result<Bsdf, SceneError> {
    let mut params = Vec::new();
    for (name, value) in model.parameters() {
        let ParamValue::Number(x) = value else { continue };
        match textured.iter().position(|(n, _)| n == name) {
            Some(k) => params.push(textured.swap_remove(k).1),
            None => params.push(Texture::Constant(Vec3::splat(x as f32))),
        }
    }
    if let Some((name, _)) = textured.first() {
        return Err(values::prop_err(obj, name, "is not a numeric parameter of this model, so it cannot be a texture"));
    }
    Ok(Bsdf::TexturedMatte(Box::new(TexturedMatte { model, reflectance, params })))
}

/// `material` (default "none": a perfect mirror) or explicit `eta` and `k`. As in Mitsuba
/// (`src/bsdfs/conductor.cpp`), `material="none"` may be spelt out next to `eta`/`k`.
fn conductor_ior(obj: &SceneObject) -> Result<(Vec3, Vec3), SceneError> {
    let has_explicit = obj.properties.contains("eta") || obj.properties.contains("k");
    if has_explicit {
        if obj.properties.contains("material") && values::string(obj, "material", "none")? != "none" {
            return Err(err(obj, "give either material or eta/k, not both"));
        }
        let eta = values::color(obj, "eta", ColorUse::Unbounded, Vec3::ZERO)?;
        let k = values::color(obj, "k", ColorUse::Unbounded, Vec3::ONE)?;
        for (name, v) in [("eta", eta), ("k", k)] {
            if v.abs().max_element() as f64 > MAX_MAGNITUDE {
                return Err(values::prop_err(obj, name, too_large(v.abs().max_element() as f64)));
            }
        }
        return Ok((eta, k));
    }
    let m = values::string(obj, "material", "none")?;
    conductor_material(&m).map_err(|e| values::prop_err(obj, "material", e))
}
