//! Textured numeric parameters of matte's models (`docs/models.md#spatially-varying-parameters`):
//! the per-lane kernels (`matte_brdf::lane`) against the constant-parameter models they must
//! equal, and the clamps that keep a texture's out-of-range values finite. (The loader's side,
//! textures in scene files, is tested in `tests/render/matte_bsdf.rs`.)

use glam::Vec3;
use matte_brdf::kernel;
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

/// The per-lane kernel with a parameter's value equals the model built with that value: the
/// same generic constructor, in f32 instead of f64 (Oren–Nayar, EON, roughdiffuse), or with
/// the fitted Fresnel average (Wolff, ≤ 2e-4 relative).
#[test]
fn lane_kernels_equal_the_constant_models() {
    type Case<'a> = (&'a str, &'a [(&'a str, f64)], f32);
    let cases: &[Case] = &[
        ("lambert", &[], 0.0),
        ("oren_nayar", &[("sigma", 0.0)], 1e-5),
        ("oren_nayar", &[("sigma", 0.45)], 1e-5),
        ("eon", &[("roughness", 0.0)], 1e-5),
        ("eon", &[("roughness", 0.8)], 1e-5),
        ("roughdiffuse", &[("alpha", 0.6)], 1e-5),
        ("wolff", &[("int_ior", 1.01), ("ext_ior", 1.0)], 2e-4),
        ("wolff", &[("int_ior", 1.6), ("ext_ior", 1.2)], 2e-4),
        ("wolff", &[("int_ior", 3.5), ("ext_ior", 1.0)], 2e-4),
    ];
    // (van Ginneken's per-lane kernel interpolates tables over m: `ginneken_fast_path.rs`.)
    for (kind, params, tol) in cases {
        for extra in [vec![], vec![("model", "full")], vec![("normalization", "normal")]] {
            let mut p: Vec<(&str, ParamValue)> = params.iter().map(|(n, v)| (*n, (*v).into())).collect();
            let applies = extra
                .iter()
                .all(|(n, _)| (*n == "model" && *kind == "oren_nayar") || (*n == "normalization" && *kind == "wolff"));
            if !applies {
                continue;
            }
            for (n, v) in &extra {
                p.push((n, (*v).into()));
            }
            let m = DiffuseModel::with(kind, &p).unwrap();
            let values: Vec<f32> = params.iter().map(|(_, v)| *v as f32).collect();
            let k = m.lane_kernel_f32(&values).expect("per-lane kernel");
            for (wi, wo) in pairs() {
                let want = m.eval(wi, wo, [0.3, 0.9, 1.0]);
                let got = kernel::eval(&k, wi.into(), wo.into(), [0.3, 0.9, 1.0]);
                for c in 0..3 {
                    let err = (got[c] - want[c]).abs() / want[c].abs().max(1e-6);
                    assert!(err <= *tol, "{kind} {params:?} {extra:?}: {} vs {} at {wi} {wo}", got[c], want[c]);
                }
            }
        }
    }
}

/// Out-of-range and NaN texture values are clamped into the valid range (σ, α ≥ 0;
/// r ∈ [0, 1]; n ≥ 1; m ∈ [0.02, 4]), so the kernel stays finite and equals the model at
/// the bound.
#[test]
fn lane_values_out_of_range_are_clamped() {
    let (wi, wo) = (Vec3::new(0.3, 0.1, 0.95).normalize(), Vec3::new(-0.6, 0.2, 0.4).normalize());
    type Case<'a> = (&'a str, &'a str, f64, &'a [f32]);
    let cases: &[Case] = &[
        ("oren_nayar", "sigma", 0.0, &[-1.0, f32::NAN, f32::NEG_INFINITY]),
        ("roughdiffuse", "alpha", 0.0, &[-0.5, f32::NAN]),
        ("eon", "roughness", 0.0, &[-3.0, f32::NAN]),
        ("eon", "roughness", 1.0, &[7.0, f32::INFINITY]),
        ("wolff", "int_ior", 1.0, &[0.2, f32::NAN, -4.0]),
        ("ginneken", "roughness", 0.02, &[0.0, -1.0, f32::NAN]),
        ("ginneken", "roughness", 4.0, &[9.0, f32::INFINITY]),
    ];
    for (kind, name, bound, values) in cases {
        let want = DiffuseModel::with(kind, &[(name, *bound)]).unwrap().eval(wi, wo, [0.7])[0];
        for &v in *values {
            let mut lane = vec![v];
            if *kind == "wolff" {
                lane.push(1.0);
            }
            let m = DiffuseModel::with::<f64>(kind, &[]).unwrap();
            let k = m.lane_kernel_f32(&lane).unwrap();
            let got = kernel::eval(&k, wi.into(), wo.into(), [0.7])[0];
            assert!(got.is_finite(), "{kind} {name} = {v}: {got}");
            // van Ginneken: the roughness axis against the single-roughness table at the bound.
            let tol = if *kind == "ginneken" { 2e-3 } else { 2e-4 };
            assert!((got - want).abs() <= tol * want, "{kind} {name} = {v}: {got} vs {want} at the bound");
        }
    }
}
