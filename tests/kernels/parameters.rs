//! Bad parameters are rejected at construction with an error naming the parameter.

use matte_brdf::{DiffuseModel, ParamValue, Params};

fn rejected(kind: &str, params: &[(&str, ParamValue)]) -> String {
    let mut p = Params::new();
    for (n, v) in params {
        p.push(n, v.clone());
    }
    match DiffuseModel::from_params(kind, p) {
        Ok(b) => panic!("{kind} {params:?} was accepted: {b:?}"),
        Err(e) => {
            let text = e.to_string();
            assert!(text.contains(&format!("\"{}\"", e.param)), "message does not name the parameter: {text}");
            e.param
        }
    }
}

use ParamValue::{Number as N, Text as T};

#[test]
fn out_of_range_values_name_their_parameter() {
    assert_eq!(rejected("oren_nayar", &[("sigma", N(-0.1))]), "sigma");
    assert_eq!(rejected("oren_nayar", &[("sigma", N(f64::NAN))]), "sigma");
    assert_eq!(rejected("oren_nayar", &[("model", T("fast".into()))]), "model");
    assert_eq!(rejected("eon", &[("roughness", N(1.5))]), "roughness");
    assert_eq!(rejected("eon", &[("roughness", N(-0.01))]), "roughness");
    assert_eq!(rejected("wolff", &[("int_ior", N(0.9))]), "int_ior");
    assert_eq!(rejected("wolff", &[("ext_ior", N(0.5))]), "ext_ior");
    assert_eq!(rejected("wolff", &[("int_ior", N(1.2)), ("ext_ior", N(1.5))]), "int_ior");
    assert_eq!(rejected("wolff", &[("int_ior", T("unobtainium".into()))]), "int_ior");
    assert_eq!(rejected("wolff", &[("normalization", T("none".into()))]), "normalization");
    assert_eq!(rejected("ginneken", &[("roughness", N(0.0))]), "roughness");
    assert_eq!(rejected("ginneken", &[("roughness", N(-1.0))]), "roughness");
    assert_eq!(rejected("ginneken", &[("roughness", N(f64::INFINITY))]), "roughness");
    assert_eq!(rejected("ginneken", &[("shadowing", T("smith".into()))]), "shadowing");
}

#[test]
fn unknown_names_are_rejected() {
    assert_eq!(rejected("lambert", &[("sigma", N(0.3))]), "sigma");
    assert_eq!(rejected("oren_nayar", &[("roughness", N(0.3))]), "roughness");
    assert_eq!(rejected("phong", &[]), "type");
    assert_eq!(rejected("eon", &[("roughness", T("rough".into()))]), "roughness");
}

#[test]
fn defaults_follow_the_seed_study() {
    let p = |kind: &str| DiffuseModel::from_params(kind, Params::new()).unwrap().parameters();
    assert_eq!(p("oren_nayar")[0], ("sigma", N(0.30000001192092896)));
    assert_eq!(p("wolff")[0], ("int_ior", N(1.399999976158142)));
    assert_eq!(p("wolff")[1], ("ext_ior", N(1.0)));
    assert_eq!(p("wolff")[2], ("normalization", T("physical".into())));
    assert_eq!(p("ginneken")[1], ("shadowing", T("vginneken".into())));
}

#[test]
fn boundary_values_are_accepted() {
    for (kind, name, v) in
        [("oren_nayar", "sigma", 0.0), ("eon", "roughness", 0.0), ("eon", "roughness", 1.0), ("wolff", "int_ior", 1.0)]
    {
        DiffuseModel::from_params(kind, Params::new().with(name, N(v)))
            .unwrap_or_else(|e| panic!("{kind} {name}={v}: {e}"));
    }
}

#[test]
fn magnitudes_beyond_the_limit_are_rejected_by_every_model() {
    // One limit for every front end (CLI, renderer, plugin): `matte_brdf::params::MAX_MAGNITUDE`.
    // Every numeric parameter of every registered model (one with a required file, `tabulated_brdf`,
    // has none).
    let mut checked = 0;
    for m in crate::common::models_from_defaults() {
        for p in m.numeric() {
            for v in [1e7, -1e7] {
                let e = DiffuseModel::from_params(m.name, Params::new().with(p.name, N(v)))
                    .expect_err(&format!("{}.{} = {v}", m.name, p.name));
                assert_eq!(e.param, p.name, "{}: {e}", m.name);
                assert!(e.to_string().contains("up to 1e6"), "{}.{} = {v}: {e}", m.name, p.name);
            }
            checked += 1;
        }
    }
    assert!(checked >= 5, "only {checked} numeric parameters");
}
