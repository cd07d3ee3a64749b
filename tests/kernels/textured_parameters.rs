//! Textured numeric parameters of matte's models (`docs/models.md#spatially-varying-parameters`):
//! the per-lane kernels (`matte_brdf::lane`) against the constant-parameter models they must
//! equal, and the clamps that keep a texture's out-of-range values finite. (The loader's side,
//! textures in scene files, is tested in `tests/render/matte_bsdf.rs`.)

use crate::common::{inner_values, models_from_defaults, sweep_bounds};
use glam::Vec3;
use matte_brdf::kernel;
use matte_brdf::registry::ModelSpec;
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue};

/// Quasi-random direction pairs above the surface, grazing included.
fn pairs() -> Vec<(Vec3, Vec3)> {
    (0..2000)
        .map(|k| {
            let f = |a: f64| ((0.5 + a * (k as f64 + 1.0)).fract()) as f32;
            let (ti, to) = (f(0.7548776662) * 1.55, f(0.5698402910) * 1.55);
            let (pi, po) = (f(0.4302966531) * std::f32::consts::TAU, f(0.2327856400) * std::f32::consts::TAU);
            let d = |t: f32, p: f32| Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
            (d(ti, pi), d(to, po))
        })
        .collect()
}

/// The numeric parameter values of `model` in order, in f32: its per-lane values.
fn lane_values_of(model: &DiffuseModel) -> Vec<f32> {
    model
        .parameters()
        .into_iter()
        .filter_map(|(_, v)| if let ParamValue::Number(x) = v { Some(x as f32) } else { None })
        .collect()
}

/// The configurations each model's examples declare besides its numeric parameters (Oren–Nayar's
/// `model`, Wolff's `normalization`, …), and the defaults: the variants the sweeps below run.
fn variants(spec: &ModelSpec) -> Vec<Vec<(&'static str, &'static str)>> {
    let mut out = vec![vec![]];
    for example in spec.examples {
        let words: Vec<(&str, &str)> =
            example.iter().copied().filter(|(n, _)| spec.param(n).is_none_or(|p| !p.is_numeric())).collect();
        if !out.contains(&words) {
            out.push(words);
        }
    }
    out
}

/// The per-lane kernel with a parameter's value equals the model built with that value: the
/// same generic constructor, in f32 instead of f64 (≤ 1e-5 relative), with the fitted Fresnel
/// average (Wolff, ≤ 2e-4), or, without numeric parameters, the same kernel (exactly). Every
/// registered model in each variant of [`variants`], each numeric parameter (the others at their
/// defaults) at the lower end of [`sweep_bounds`] and at [`inner_values`], where the model accepts it.
#[test]
fn lane_kernels_equal_the_constant_models() {
    let mut checked = 0;
    // (van Ginneken's per-lane kernel interpolates tables over m: `ginneken_fast_path.rs`.)
    for spec in models_from_defaults().filter(|s| s.name != "ginneken") {
        let tol: f32 = match spec.name {
            _ if spec.numeric().next().is_none() => 0.0,
            "wolff" => 2e-4,
            _ => 1e-5,
        };
        for words in variants(spec) {
            let words: Vec<(&str, ParamValue)> = words.iter().map(|(n, v)| (*n, ParamValue::parse(v))).collect();
            let mut configurations = vec![words.clone()];
            for p in spec.numeric() {
                for x in std::iter::once(sweep_bounds(p).0).chain(inner_values(p)) {
                    let mut c = words.clone();
                    c.push((p.name, ParamValue::Number(x)));
                    configurations.push(c);
                }
            }
            for params in configurations {
                let Ok(m) = DiffuseModel::with(spec.name, &params) else { continue };
                let k = m.lane_kernel_f32(&lane_values_of(&m)).expect("per-lane kernel");
                for (wi, wo) in pairs() {
                    let want = m.eval(wi, wo, [0.3, 0.9, 1.0]);
                    let got = kernel::eval(&k, wi.into(), wo.into(), [0.3, 0.9, 1.0]);
                    for c in 0..3 {
                        let err = (got[c] - want[c]).abs() / want[c].abs().max(1e-6);
                        assert!(err <= tol, "{} {params:?}: {} vs {} at {wi} {wo}", spec.name, got[c], want[c]);
                    }
                }
                checked += 1;
            }
        }
    }
    assert!(checked >= 40, "only {checked} configurations");
}

/// Out-of-range and NaN texture values are clamped into each numeric parameter's lane clamp
/// (σ, α ≥ 0; r ∈ [0, 1]; n ≥ 1; m ∈ [0.02, 4]; the registry's), so the kernel stays finite and
/// equals the model at the bound. Every numeric parameter of every registered model, the
/// others at their defaults.
#[test]
fn lane_values_out_of_range_are_clamped() {
    let (wi, wo) = (Vec3::new(0.3, 0.1, 0.95).normalize(), Vec3::new(-0.6, 0.2, 0.4).normalize());
    let mut checked = 0;
    for spec in models_from_defaults() {
        let m = DiffuseModel::with::<f64>(spec.name, &[]).unwrap();
        let defaults = lane_values_of(&m);
        for (k, p) in spec.numeric().enumerate() {
            let (lo, hi) = p.lane_clamp;
            let mut cases: Vec<(f64, Vec<f32>)> = Vec::new();
            if lo.is_finite() {
                let below = [lo - 0.02, lo - 1.0, lo - 5.0].map(|x| x as f32);
                cases.push((lo, below.into_iter().chain([f32::NAN, f32::NEG_INFINITY]).collect()));
            }
            if hi.is_finite() {
                cases.push((hi, vec![(hi + 0.5) as f32, (hi + 5.0) as f32, f32::INFINITY]));
            }
            for (bound, values) in cases {
                let want = DiffuseModel::with(spec.name, &[(p.name, bound)])
                    .unwrap_or_else(|e| panic!("{}.{} = {bound}: {e}", spec.name, p.name))
                    .eval(wi, wo, [0.7])[0];
                for v in values {
                    let mut lane = defaults.clone();
                    lane[k] = v;
                    let clamped = m.lane_kernel_f32(&lane).unwrap();
                    let got = kernel::eval(&clamped, wi.into(), wo.into(), [0.7])[0];
                    assert!(got.is_finite(), "{} {} = {v}: {got}", spec.name, p.name);
                    // van Ginneken: the roughness axis against the single-roughness table at the bound.
                    let tol = if spec.name == "ginneken" { 2e-3 } else { 2e-4 };
                    assert!(
                        (got - want).abs() <= tol * want,
                        "{} {} = {v}: {got} vs {want} at the bound",
                        spec.name,
                        p.name
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 30, "only {checked} values");
}
