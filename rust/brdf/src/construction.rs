//! A model from the properties of its `<bsdf>` element, textures included: the one
//! construction path of the front ends that read scenes (the renderer's loader,
//! `rust/render/src/bsdf/matte.rs`, and the Mitsuba plugin, `cpp/matte_bsdf.h` through
//! `rust/plugin/src/`), the CLI and every model built from name–value pairs
//! ([`DiffuseModel::with`]). A front end collects the element's properties as [`ParamValue`]s
//! (a nested texture as [`ParamValue::Texture`], its mean), calls [`construct`] and, for the
//! numeric parameters the result marks textured, evaluates its own texture objects per hit
//! (`docs/models.md#spatially-varying-parameters`).

use crate::lane::{numeric_parameter_names, textured_placeholder};
use crate::params::{ParamError, ParamValue, Params, lookup_ior};
use crate::registry::spec::ParamKind;
use crate::{DiffuseModel, spec};

/// A numeric parameter of the constructed model, in the order per-lane values are given
/// ([`crate::registry::ModelSpec::numeric`]).
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
    spec(kind).and_then(|s| s.param(name)).is_some_and(|p| p.kind == ParamKind::File)
}

/// The model `kind` (a plugin name) from `properties` (`reflectance` excepted: it is not a
/// model parameter but an input of every evaluation). Errors name the parameter: an unknown
/// type, an unknown parameter, a value out of range, or a texture for a parameter that is not
/// numeric.
pub fn construct<S: AsRef<str>>(kind: &str, properties: &[(S, ParamValue)]) -> Result<Construction, ParamError> {
    if spec(kind).is_none() {
        // The unknown type's error, listing the known ones.
        DiffuseModel::from_params(kind, Params::new())?;
    }
    let numeric_names = numeric_parameter_names(kind);
    let is_texture =
        |name: &str| properties.iter().any(|(n, p)| n.as_ref() == name && matches!(p, ParamValue::Texture { .. }));
    if let Some((name, _)) =
        properties.iter().find(|(n, p)| matches!(p, ParamValue::Texture { .. }) && !numeric_names.contains(&n.as_ref()))
    {
        return Err(ParamError::new(
            name.as_ref(),
            "is not a numeric parameter of this model, so it cannot be a texture",
        ));
    }
    // Another parameter's value as a number (Wolff's indices bound each other: int ≥ ext).
    let number = |other: &str| match properties.iter().find(|(n, _)| n.as_ref() == other).map(|(_, p)| p) {
        Some(ParamValue::Number(x)) => Some(*x),
        Some(ParamValue::Text(s)) => lookup_ior(s),
        _ => None,
    };
    let mut params = Params::new();
    for (name, p) in properties {
        let name = name.as_ref();
        let value = match p {
            ParamValue::Texture { mean } => ParamValue::Number(textured_placeholder(kind, name, *mean, number)),
            other => other.clone(),
        };
        params.push(name, value);
    }
    let model = DiffuseModel::from_params(kind, params)?;
    let numeric = model
        .parameters()
        .into_iter()
        .filter_map(|(name, value)| match value {
            ParamValue::Number(value) => Some(Numeric { name, value, textured: is_texture(name) }),
            _ => None,
        })
        .collect();
    Ok(Construction { model, numeric })
}

impl DiffuseModel {
    /// The model `kind` (a plugin name) from `(name, value)` pairs, through [`construct`]:
    /// `DiffuseModel::with("eon", &[("roughness", 0.5)])`; for values of several types, pairs
    /// of [`ParamValue`]. Errors name the parameter.
    pub fn with<V: Clone + Into<ParamValue>>(kind: &str, pairs: &[(&str, V)]) -> Result<Self, ParamError> {
        let properties: Vec<(&str, ParamValue)> = pairs.iter().map(|(n, v)| (*n, v.clone().into())).collect();
        construct(kind, &properties).map(|c| c.model)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_texture_stands_for_its_clamped_mean_and_is_marked() {
        let c = construct(
            "oren_nayar",
            &[("sigma", ParamValue::Texture { mean: -1.0 }), ("model", ParamValue::Text("full".into()))],
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
            &[("ext_ior", ParamValue::Text("water".into())), ("int_ior", ParamValue::Texture { mean: 1.0 })],
        )
        .unwrap();
        let int = c.numeric.iter().find(|n| n.name == "int_ior").unwrap();
        assert!(int.textured && (int.value - water).abs() < 1e-6, "{int:?}");
    }

    #[test]
    fn errors_name_the_parameter() {
        let e = construct("eon", &[("sampling", ParamValue::Texture { mean: 0.5 })]).unwrap_err();
        assert_eq!(e.param, "sampling");
        assert!(e.message.contains("not a numeric parameter"), "{e}");
        let e = construct("nope", &[("sigma", ParamValue::Texture { mean: 0.5 })]).unwrap_err();
        assert!(e.message.contains("unknown bsdf type"), "{e}");
        let e = construct("eon", &[("roughness", ParamValue::Number(-1.0))]).unwrap_err();
        assert_eq!(e.param, "roughness");
        let e = construct("eon", &[("colour", ParamValue::Number(1.0))]).unwrap_err();
        assert_eq!(e.param, "colour");
    }
}
