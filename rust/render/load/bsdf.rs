//! `<bsdf>`: Mitsuba's `diffuse`, `twosided`, `dielectric`, `conductor`, `roughconductor`
//! and matte's `lambert`, `oren_nayar`, `eon`, `wolff`, `ginneken`, `roughdiffuse` (parameters validated by
//! the kernels' own parser, the same one the Mitsuba plugin uses).

use super::{Builder, err, texture, values};
use crate::brdf::{ParamValue, Params, BSDF_TYPES};
use crate::render::bsdf::{Bsdf, Conductor, Dielectric, MicrofacetDistribution, RoughConductor, Texture, conductor_material};
use crate::scene::SceneError;
use crate::scene::xml::{ColorUse, SceneObject, Value};
use glam::Vec3;

/// The BSDF index for this XML object, building it the first time it is seen.
pub fn get_or_build(b: &mut Builder, obj: &SceneObject) -> Result<u32, SceneError> {
    let key = obj as *const SceneObject;
    if let Some(&i) = b.bsdf_index.get(&key) {
        return Ok(i);
    }
    let bsdf = build(b, obj)?;
    b.bsdfs.push(bsdf);
    let i = (b.bsdfs.len() - 1) as u32;
    b.bsdf_index.insert(key, i);
    Ok(i)
}

/// A constant-colour diffuse BSDF (Mitsuba's default for shapes without one).
pub fn default_diffuse(b: &mut Builder, reflectance: f32) -> u32 {
    b.bsdfs.push(Bsdf::Diffuse { reflectance: Texture::Constant(Vec3::splat(reflectance)) });
    (b.bsdfs.len() - 1) as u32
}

fn build(b: &mut Builder, obj: &SceneObject) -> Result<Bsdf, SceneError> {
    let bsdf = match obj.plugin.as_str() {
        "diffuse" => Bsdf::Diffuse { reflectance: texture::get(b, obj, "reflectance", ColorUse::Bounded, Vec3::splat(0.5))? },
        kind if BSDF_TYPES.contains(&kind) => {
            let reflectance = texture::get(b, obj, "reflectance", ColorUse::Bounded, Vec3::splat(0.5))?;
            let mut params = Params::new();
            for p in obj.properties.iter().filter(|p| p.name != "reflectance") {
                let value = match &p.value {
                    Value::Float(x) if x.abs() > MAX_MAGNITUDE => return Err(values::prop_err(obj, &p.name, too_large(*x))),
                    Value::Integer(i) if (*i as f64).abs() > MAX_MAGNITUDE => return Err(values::prop_err(obj, &p.name, too_large(*i as f64))),
                    Value::Float(x) => ParamValue::Number(*x),
                    Value::Integer(i) => ParamValue::Number(*i as f64),
                    Value::String(s) => ParamValue::Text(s.clone()),
                    Value::Boolean(v) => ParamValue::Text(v.to_string()),
                    other => return Err(values::prop_err(obj, &p.name, format!("must be a number or a string, not {}", other.type_name()))),
                };
                p.used.set(true);
                params.push(&p.name, value);
            }
            let model = crate::brdf::Bsdf::from_params(kind, params).map_err(|e| values::prop_err(obj, &e.param, e.message))?;
            Bsdf::Matte { model, reflectance }
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
            for side in [&front, &back] {
                if matches!(side, Bsdf::Dielectric(_)) {
                    return Err(err(obj, "a twosided BSDF cannot wrap a transmissive BSDF (as in Mitsuba)"));
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
            // Case-insensitive, as Mitsuba's `string::to_lower` (src/bsdfs/roughconductor.cpp).
            let distribution = match values::string(obj, "distribution", "beckmann")?.to_lowercase().as_str() {
                "beckmann" => MicrofacetDistribution::Beckmann,
                "ggx" => MicrofacetDistribution::Ggx,
                other => return Err(values::prop_err(obj, "distribution", format!("must be beckmann or ggx, got \"{other}\""))),
            };
            let names = match (obj.properties.contains("alpha_u"), obj.properties.contains("alpha_v")) {
                (false, false) => ["alpha", "alpha"],
                (true, true) => ["alpha_u", "alpha_v"],
                _ => return Err(err(obj, "alpha_u and alpha_v must be given together")),
            };
            let (au, av) = (values::float(obj, names[0], 0.1)?, values::float(obj, names[1], 0.1)?);
            // α = 0 is valid: Mitsuba (and RoughConductor::new) raise it to 1e-4. A negative
            // roughness Mitsuba would take silently is an error here.
            for (n, a) in [(names[0], au), (names[1], av)] {
                if !(a.is_finite() && a >= 0.0) {
                    return Err(values::prop_err(obj, n, format!("roughness must be finite and ≥ 0, got {a}")));
                }
                if a > MAX_MAGNITUDE {
                    return Err(values::prop_err(obj, n, too_large(a)));
                }
            }
            let sample_visible = values::boolean(obj, "sample_visible", true)?;
            let (eta, k) = conductor_ior(obj)?;
            let r = constant(obj, "specular_reflectance")?;
            Bsdf::RoughConductor(RoughConductor::new(distribution, au as f32, av as f32, sample_visible, eta, k, r).map_err(|e| err(obj, e))?)
        }
        other => {
            return Err(err(
                obj,
                format!("unsupported bsdf type \"{other}\" (matte renders: diffuse, twosided, dielectric, conductor, roughconductor, {})", BSDF_TYPES.join(", ")),
            ));
        }
    };
    obj.check_all_used()?;
    Ok(bsdf)
}

/// A float or a named IOR (Mitsuba's table, shared with the kernels).
fn ior(obj: &SceneObject, name: &str, default: f64) -> Result<f32, SceneError> {
    let v = match obj.properties.get(name).map(|p| p.value.clone()) {
        None => default,
        Some(Value::String(s)) => crate::brdf::params::lookup_ior(&s).ok_or_else(|| values::prop_err(obj, name, format!("unknown IOR name \"{s}\"")))?,
        Some(_) => values::float(obj, name, default)?,
    };
    if !(v.is_finite() && v >= 1.0) {
        return Err(values::prop_err(obj, name, format!("must be ≥ 1, got {v}")));
    }
    if v > MAX_MAGNITUDE {
        return Err(values::prop_err(obj, name, too_large(v)));
    }
    Ok(v as f32)
}

/// Largest magnitude matte accepts for a BSDF number (IORs, η/k, roughness, the matte
/// kernels' parameters). Mitsuba takes any float, but the f32 kernels overflow into NaN
/// around 1e15–1e19 (e.g. η⁴ in the conductor Fresnel term), long after values stopped
/// meaning anything physically.
const MAX_MAGNITUDE: f64 = 1e6;

fn too_large(v: f64) -> String {
    format!("is {v}; matte accepts magnitudes up to {MAX_MAGNITUDE:e}")
}

/// `specular_*` weights: constant colours only (default 1).
fn constant(obj: &SceneObject, name: &str) -> Result<Vec3, SceneError> {
    if obj.child(name).is_some() {
        return Err(err(obj, format!("a texture for \"{name}\" is not supported by matte render")));
    }
    values::color(obj, name, ColorUse::Bounded, Vec3::ONE)
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
