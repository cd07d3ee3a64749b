//! A model from the properties of its `<bsdf>` element, textures included: the one
//! construction path of the front ends that read scenes (the renderer's loader,
//! `rust/render/src/bsdf/matte.rs`, and the Mitsuba plugin, `cpp/matte_bsdf.h` through
//! `rust/plugin/src/`). A front end collects the element's properties as [`Property`] values (for a
//! nested texture, its mean), calls [`construct`] and, for the numeric parameters the result
//! marks textured, evaluates its own texture objects per hit
//! (`docs/models.md#spatially-varying-parameters`).

use super::lane::{numeric_parameter_names, textured_placeholder};
use super::params::lookup_ior;
use super::{DiffuseModel, ParamError, ParamValue, Params, spec};

/// One property of a `<bsdf>` element as a front end read it (`reflectance` excepted: it is
/// not a model parameter but an input of every evaluation).
#[derive(Clone, Debug, PartialEq)]
pub enum Property {
    /// `<float>` or `<integer>`.
    Number(f64),
    /// `<string>` (a choice, or a named index of refraction).
    Text(String),
    /// `<boolean>`.
    Flag(bool),
    /// A nested `<texture>`, given by its mean: the number the parameter stands for when the
    /// model is built and validated (clamped into the parameter's per-lane range, so any
    /// texture is accepted; its values are clamped per lane).
    Texture { mean: f64 },
}

/// A numeric parameter of the constructed model, in the order per-lane values are given
/// ([`super::registry::ModelSpec::numeric`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Numeric {
    pub name: &'static str,
    /// Its effective value (the default filled in; for a texture, the placeholder).
    pub value: f64,
    /// Whether a texture gives it: the front end evaluates that texture per hit.
    pub textured: bool,
}

/// What [`construct`] gives a front end.
#[derive(Clone, Debug)]
pub struct Construction {
    pub model: DiffuseModel,
    pub numeric: Vec<Numeric>,
}

impl Construction {
    /// Whether a numeric parameter is a texture (evaluated per hit).
    pub fn is_textured(&self) -> bool {
        self.numeric.iter().any(|n| n.textured)
    }
}

/// Whether `name` is a file parameter of the model `kind` (`tabulated_brdf`'s `filename`): the
/// front end resolves it as it resolves a scene's files before handing it to [`construct`].
pub fn is_file_parameter(kind: &str, name: &str) -> bool {
    spec(kind).and_then(|s| s.param(name)).is_some_and(|p| p.kind == super::registry::ParamKind::File)
}

/// The model `kind` (a plugin name) from `properties`. Errors name the parameter: an unknown
/// type, an unknown parameter, a value out of range, or a texture for a parameter that is not
/// numeric.
pub fn construct<S: AsRef<str>>(kind: &str, properties: &[(S, Property)]) -> Result<Construction, ParamError> {
    if spec(kind).is_none() {
        // The unknown type's error, listing the known ones.
        DiffuseModel::from_params(kind, Params::new())?;
    }
    let numeric_names = numeric_parameter_names(kind);
    let is_texture =
        |name: &str| properties.iter().any(|(n, p)| n.as_ref() == name && matches!(p, Property::Texture { .. }));
    if let Some((name, _)) =
        properties.iter().find(|(n, p)| matches!(p, Property::Texture { .. }) && !numeric_names.contains(&n.as_ref()))
    {
        return Err(ParamError::new(
            name.as_ref(),
            "is not a numeric parameter of this model, so it cannot be a texture",
        ));
    }
    // Another parameter's value as a number (Wolff's indices bound each other: int ≥ ext).
    let number = |other: &str| match properties.iter().find(|(n, _)| n.as_ref() == other).map(|(_, p)| p) {
        Some(Property::Number(x)) => Some(*x),
        Some(Property::Text(s)) => lookup_ior(s),
        _ => None,
    };
    let mut params = Params::new();
    for (name, p) in properties {
        let name = name.as_ref();
        let value = match p {
            Property::Number(x) => ParamValue::Number(*x),
            Property::Text(s) => ParamValue::Text(s.clone()),
            Property::Flag(b) => ParamValue::Text(b.to_string()),
            Property::Texture { mean } => ParamValue::Number(textured_placeholder(kind, name, *mean, number)),
        };
        params.push(name, value);
    }
    let model = DiffuseModel::from_params(kind, params)?;
    let numeric = model
        .parameters()
        .into_iter()
        .filter_map(|(name, value)| match value {
            ParamValue::Number(value) => Some(Numeric { name, value, textured: is_texture(name) }),
            ParamValue::Text(_) => None,
        })
        .collect();
    Ok(Construction { model, numeric })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_texture_stands_for_its_clamped_mean_and_is_marked() {
        let c = construct(
            "oren_nayar",
            &[("sigma", Property::Texture { mean: -1.0 }), ("model", Property::Text("full".into()))],
        )
        .unwrap();
        // σ ≥ 0: a texture of negative mean stands for 0.
        assert_eq!(c.numeric, vec![Numeric { name: "sigma", value: 0.0, textured: true }]);
        assert!(c.is_textured());
    }

    #[test]
    fn a_named_index_bounds_a_textured_one() {
        // Wolff: int_ior ≥ ext_ior, with ext_ior a named material and int_ior a texture below
        // it: the texture stands for water's index (as the model stores it, in f32).
        let water = lookup_ior("water").unwrap();
        let c = construct(
            "wolff",
            &[("ext_ior", Property::Text("water".into())), ("int_ior", Property::Texture { mean: 1.0 })],
        )
        .unwrap();
        let int = c.numeric.iter().find(|n| n.name == "int_ior").unwrap();
        assert!(int.textured && (int.value - water).abs() < 1e-6, "{int:?}");
    }

    #[test]
    fn errors_name_the_parameter() {
        let e = construct("eon", &[("sampling", Property::Texture { mean: 0.5 })]).unwrap_err();
        assert_eq!(e.param, "sampling");
        assert!(e.message.contains("not a numeric parameter"), "{e}");
        let e = construct("nope", &[("sigma", Property::Texture { mean: 0.5 })]).unwrap_err();
        assert!(e.message.contains("unknown bsdf type"), "{e}");
        let e = construct("eon", &[("roughness", Property::Number(-1.0))]).unwrap_err();
        assert_eq!(e.param, "roughness");
        let e = construct("eon", &[("colour", Property::Number(1.0))]).unwrap_err();
        assert_eq!(e.param, "colour");
    }
}
