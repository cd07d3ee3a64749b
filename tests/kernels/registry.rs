//! The model registry (`matte_brdf::registry`): every registered model obeys its own
//! declaration. Ranges: both ends accepted where closed, values just outside rejected naming
//! the parameter. Defaults: a model built from nothing reports its declared defaults. Lane
//! clamps: a per-lane value beyond the clamp evaluates as the bound, NaN as the lower bound,
//! and an in-range value as the constant model. Examples build. The README's model table is
//! the registry's (`matte types --markdown`).

use matte_brdf::kernel;
use matte_brdf::registry::{ParamKind, Range};
use matte_brdf::{BSDF_TYPES, DiffuseBrdf, DiffuseModel, MODELS, ParamValue};
use std::collections::HashSet;

use crate::common::{Pcg32, PcgExt};

#[test]
fn names_are_unique_and_listed_in_order() {
    let names: Vec<&str> = MODELS.iter().map(|m| m.name).collect();
    assert_eq!(names, BSDF_TYPES);
    assert_eq!(names.iter().collect::<HashSet<_>>().len(), names.len());
    for m in MODELS {
        let params: HashSet<&str> = m.params.iter().map(|p| p.name).collect();
        assert_eq!(params.len(), m.params.len(), "{}: a parameter declared twice", m.name);
        assert!(!params.contains("reflectance"), "{}: reflectance is every model's, not a parameter", m.name);
        assert!(matte_brdf::registry::numeric_count(m) <= matte_brdf::registry::MAX_NUMERIC);
    }
}

#[test]
fn defaults_are_the_declared_ones() {
    for m in MODELS {
        if !m.builds_from_defaults() {
            // A required parameter (`tabulated_brdf`'s file) left out is an error naming it.
            let e = DiffuseModel::with::<ParamValue>(m.name, &[]).expect_err(m.name);
            assert!(m.param(&e.param).is_some_and(|p| p.default_value().is_none()), "{}: {e}", m.name);
            continue;
        }
        let model = DiffuseModel::with::<ParamValue>(m.name, &[])
            .unwrap_or_else(|e| panic!("{}: defaults rejected: {e}", m.name));
        assert_eq!(model.kind(), m.name);
        let got = model.parameters();
        assert_eq!(got.len(), m.params.len(), "{}", m.name);
        for ((name, value), p) in got.iter().zip(m.params) {
            assert_eq!(*name, p.name);
            match (value, p.default_value().expect("a default")) {
                (ParamValue::Number(x), ParamValue::Number(d)) => assert_eq!(*x, d as f32 as f64, "{}.{name}", m.name),
                (v, d) => assert_eq!(*v, d, "{}.{name}", m.name),
            }
        }
    }
}

#[test]
fn examples_build() {
    for m in MODELS {
        for ex in m.examples {
            let params: Vec<(&str, ParamValue)> = ex.iter().map(|(n, v)| (*n, ParamValue::parse(v))).collect();
            DiffuseModel::with(m.name, &params).unwrap_or_else(|e| panic!("{} {ex:?}: {e}", m.name));
        }
    }
}

#[test]
fn ranges_are_enforced_at_their_ends() {
    for m in MODELS {
        for p in m.numeric() {
            let (accepted, rejected): (Vec<f64>, Vec<f64>) = match p.range {
                Range::AtLeast(lo) => (vec![lo, lo + 1.0], vec![lo - 1e-3]),
                Range::Closed(lo, hi) => (vec![lo, hi], vec![lo - 1e-3, hi + 1e-3]),
                Range::OpenClosed(lo, hi) => (vec![lo + 1e-3, hi], vec![lo, hi + 1e-3]),
            };
            // A second index must not make an accepted value invalid (Wolff: int ≥ ext).
            let with = |x: f64| {
                let mut v = vec![(p.name, ParamValue::Number(x))];
                if matches!(p.kind, ParamKind::Ior { .. }) {
                    for q in m.numeric().filter(|q| q.name != p.name) {
                        v.push((q.name, ParamValue::Number(1.0f64.max(if q.name == "ext_ior" { 1.0 } else { x }))));
                    }
                }
                v
            };
            for x in accepted {
                DiffuseModel::with(m.name, &with(x))
                    .unwrap_or_else(|e| panic!("{}.{} = {x} rejected: {e}", m.name, p.name));
            }
            for x in rejected.into_iter().chain([f64::NAN, f64::INFINITY]) {
                let e = DiffuseModel::with(m.name, &[(p.name, ParamValue::Number(x))])
                    .expect_err(&format!("{}.{} = {x}", m.name, p.name));
                assert_eq!(e.param, p.name, "{}: {e}", m.name);
            }
        }
        for p in m.params.iter().filter(|p| matches!(p.kind, ParamKind::Choice { .. })) {
            let e =
                DiffuseModel::with(m.name, &[(p.name, ParamValue::Text("no such choice".into()))]).expect_err(p.name);
            assert_eq!(e.param, p.name);
        }
    }
}

/// The f32 per-lane kernel's `f` at a few random direction pairs.
fn lane_values(model: &DiffuseModel, values: &[f32], rng: &mut Pcg32) -> Vec<f32> {
    let k = model.lane_kernel_f32(values).expect("enough values");
    (0..64)
        .map(|_| {
            let (wi, wo) = (rng.upper_hemisphere(), rng.upper_hemisphere());
            kernel::eval(&k, wi.into(), wo.into(), [0.7])[0]
        })
        .collect()
}

#[test]
fn lane_values_clamp_to_the_declared_bounds() {
    // The models with numeric parameters build from their defaults (a table file has none).
    for m in MODELS.iter().filter(|m| m.builds_from_defaults()) {
        let model = DiffuseModel::with::<ParamValue>(m.name, &[]).unwrap();
        let defaults: Vec<f32> = model
            .parameters()
            .into_iter()
            .filter_map(|(_, v)| if let ParamValue::Number(x) = v { Some(x as f32) } else { None })
            .collect();
        for (k, p) in m.numeric().enumerate() {
            let at = |x: f32| {
                let mut v = defaults.clone();
                v[k] = x;
                lane_values(&model, &v, &mut Pcg32::new(7, 1))
            };
            let (lo, hi) = p.lane_clamp;
            if matches!(p.kind, ParamKind::Number { .. }) {
                assert_eq!(at(f32::NAN), at(lo as f32), "{}.{}: NaN is the lower bound", m.name, p.name);
                assert_eq!(at((lo - 0.5) as f32), at(lo as f32), "{}.{} below the clamp", m.name, p.name);
            }
            if hi.is_finite() {
                assert_eq!(at((hi + 0.5) as f32), at(hi as f32), "{}.{} above the clamp", m.name, p.name);
            }
        }
    }
}

#[test]
fn in_range_lane_values_evaluate_as_the_constant_model() {
    let mut rng = Pcg32::new(3, 5);
    for m in MODELS {
        let Some(p) = m.numeric().next() else { continue };
        let (lo, hi) = p.lane_clamp;
        let hi = if hi.is_finite() { hi } else { lo + 2.0 };
        for t in [0.1, 0.5, 0.9] {
            let x = (lo + t * (hi - lo)) as f32;
            let model = DiffuseModel::with(m.name, &[(p.name, ParamValue::Number(x as f64))]).unwrap();
            let values: Vec<f32> = model
                .parameters()
                .into_iter()
                .filter_map(|(_, v)| if let ParamValue::Number(x) = v { Some(x as f32) } else { None })
                .collect();
            let k = model.lane_kernel_f32(&values).unwrap();
            for _ in 0..200 {
                let (wi, wo) = (rng.upper_hemisphere(), rng.upper_hemisphere());
                let lane = kernel::eval(&k, wi.into(), wo.into(), [0.6])[0];
                let constant = model.eval(wi, wo, [0.6])[0];
                // van Ginneken's lane kernel interpolates tables stacked over m (0.6 %, tests/ginneken_fast_path.rs).
                let tol = if m.name == "ginneken" { 6e-3 } else { 2e-4 };
                assert!(
                    (lane - constant).abs() <= tol * constant.abs() + 1e-6,
                    "{} {}={x}: lane {lane} constant {constant}",
                    m.name,
                    p.name
                );
            }
        }
    }
}
