//! `<bsdf>`: Mitsuba's `diffuse`, `twosided`, `dielectric`, `thindielectric`, `roughdielectric`,
//! `conductor`, `roughconductor`, `plastic`, `roughplastic`, `normalmap`, `principled` and matte's `lambert`, `oren_nayar`,
//! `eon`, `wolff`, `ginneken` (parameters validated by the kernels' own parser, the same one the
//! Mitsuba plugin uses).

use super::{Builder, err, texture, values};
use crate::brdf::{ParamValue, Params, BSDF_TYPES};
use super::bsdf_params::{MAX_MAGNITUDE, constant, ior, microfacet, optional_constant, relative_ior, too_large};
use crate::render::bsdf::{
    Bsdf, Conductor, Dielectric, NormalMap, Plastic, Principled, RoughConductor, RoughDielectric, RoughPlastic, Texture, ThinDielectric, conductor_material,
};
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
                let transmissive = match side {
                    Bsdf::Dielectric(_) | Bsdf::RoughDielectric(_) | Bsdf::ThinDielectric(_) => true,
                    Bsdf::Principled(p) => p.spec_trans.is_some(),
                    _ => false,
                };
                if transmissive {
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
            let mf = microfacet(obj, true)?;
            let (eta, k) = conductor_ior(obj)?;
            let r = constant(obj, "specular_reflectance")?;
            Bsdf::RoughConductor(RoughConductor::new(mf.kind, mf.alpha_u, mf.alpha_v, mf.sample_visible, eta, k, r).map_err(|e| err(obj, e))?)
        }
        "thindielectric" => {
            let eta = ior(obj, "int_ior", 1.5046)? / ior(obj, "ext_ior", 1.000277)?;
            let r = constant(obj, "specular_reflectance")?;
            let t = constant(obj, "specular_transmittance")?;
            Bsdf::ThinDielectric(ThinDielectric::new(eta, r, t).map_err(|e| err(obj, e))?)
        }
        "roughdielectric" => {
            let mf = microfacet(obj, true)?;
            let eta = relative_ior(obj, 1.5046)?;
            let r = constant(obj, "specular_reflectance")?;
            let t = constant(obj, "specular_transmittance")?;
            Bsdf::RoughDielectric(RoughDielectric::new(mf.kind, mf.alpha_u, mf.alpha_v, mf.sample_visible, eta, r, t).map_err(|e| err(obj, e))?)
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
            Bsdf::NormalMap(NormalMap { normals, nested: Box::new(build(b, inner)?), flip_invalid_normals, use_shadowing_function })
        }
        "principled" => Bsdf::Principled(Box::new(principled(b, obj)?)),
        "plastic" => {
            let eta = ior(obj, "int_ior", 1.49)? / ior(obj, "ext_ior", 1.000277)?;
            let diffuse = texture::get(b, obj, "diffuse_reflectance", ColorUse::Bounded, Vec3::splat(0.5))?;
            let specular = optional_constant(obj, "specular_reflectance")?;
            let nonlinear = values::boolean(obj, "nonlinear", false)?;
            Bsdf::Plastic(Box::new(Plastic::new(eta, diffuse, specular, nonlinear).map_err(|e| err(obj, e))?))
        }
        "roughplastic" => {
            let mf = microfacet(obj, false)?;
            let eta = relative_ior(obj, 1.49)?;
            let diffuse = texture::get(b, obj, "diffuse_reflectance", ColorUse::Bounded, Vec3::splat(0.5))?;
            let specular = optional_constant(obj, "specular_reflectance")?;
            let nonlinear = values::boolean(obj, "nonlinear", false)?;
            Bsdf::RoughPlastic(Box::new(
                RoughPlastic::new(mf.kind, mf.alpha_u, mf.sample_visible, eta, diffuse, specular, nonlinear).map_err(|e| err(obj, e))?,
            ))
        }
        other => {
            return Err(err(
                obj,
                format!(
                    "unsupported bsdf type \"{other}\" (matte renders: diffuse, twosided, dielectric, thindielectric, roughdielectric, \
                     conductor, roughconductor, plastic, roughplastic, normalmap, principled, {})", BSDF_TYPES.join(", ")),
            ));
        }
    };
    obj.check_all_used()?;
    Ok(bsdf)
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

/// Mitsuba's `principled` (`src/bsdfs/principled.cpp`): every parameter may be a texture; an
/// optional lobe exists when its parameter is given and is not the float 0 (`get_flag`).
fn principled(b: &Builder, obj: &SceneObject) -> Result<Principled, SceneError> {
    let tex = |name: &str, default: f32| texture::get(b, obj, name, ColorUse::Bounded, Vec3::splat(default));
    let flagged = |name: &str| -> Result<Option<Texture>, SceneError> {
        let given_as_zero = matches!(obj.properties.get(name).map(|p| &p.value), Some(Value::Float(x)) if *x == 0.0);
        let given = obj.properties.contains(name) || obj.children.iter().any(|c| c.name.as_deref() == Some(name));
        let t = tex(name, 0.0)?;
        Ok(if given && !given_as_zero { Some(t) } else { None })
    };
    let base_color = tex("base_color", 0.5)?;
    let roughness = tex("roughness", 0.5)?;
    let anisotropic = flagged("anisotropic")?;
    let spec_trans = flagged("spec_trans")?;
    let sheen = flagged("sheen")?;
    let sheen_tint = flagged("sheen_tint")?;
    let flatness = flagged("flatness")?;
    let spec_tint = flagged("spec_tint")?;
    let metallic = flagged("metallic")?;
    let clearcoat = flagged("clearcoat")?;
    let clearcoat_gloss = tex("clearcoat_gloss", 0.0)?;
    let rate = |name: &str| -> Result<f32, SceneError> {
        let v = values::float(obj, name, 1.0)?;
        if !(v.is_finite() && v >= 0.0 && v <= MAX_MAGNITUDE) {
            return Err(values::prop_err(obj, name, format!("must be a finite sampling rate ≥ 0, got {v}")));
        }
        Ok(v as f32)
    };
    let (spec_srate, clearcoat_srate, diff_refl_srate) =
        (rate("main_specular_sampling_rate")?, rate("clearcoat_sampling_rate")?, rate("diffuse_reflectance_sampling_rate")?);
    if obj.properties.contains("eta") && obj.properties.contains("specular") {
        return Err(err(obj, "give either eta or specular, not both (as in Mitsuba)"));
    }
    let eta = values::float_opt(obj, "eta")?;
    if let Some(e) = eta
        && !(e.is_finite() && e > 0.0 && e <= MAX_MAGNITUDE)
    {
        return Err(values::prop_err(obj, "eta", format!("must be a positive finite index, got {e}")));
    }
    let specular = values::float_opt(obj, "specular")?;
    if let Some(s) = specular
        && !(s.is_finite() && (0.0..12.5).contains(&s))
    {
        return Err(values::prop_err(obj, "specular", format!("must be in [0, 12.5) (η = 2/(1 − √(0.08·specular)) − 1), got {s}")));
    }
    let eta = Principled::eta_from(eta.map(|e| e as f32), specular.map(|s| s as f32), spec_trans.is_some());
    Ok(Principled {
        base_color,
        roughness,
        anisotropic,
        spec_trans,
        sheen,
        sheen_tint,
        flatness,
        spec_tint,
        metallic,
        clearcoat,
        clearcoat_gloss,
        spec_srate,
        clearcoat_srate,
        diff_refl_srate,
        eta,
    })
}
