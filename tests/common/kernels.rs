//! Helpers of the kernel tests (the fast tier, `matte-brdf` alone), shared with the others
//! through `common`: PCG32 (the generator Mitsuba's samplers use) with test draws, the
//! catalogue of model configurations every property test runs over, and Mitsuba's chi-square
//! goodness-of-fit test re-implemented (`src/python/python/chi2.py` and `mitsuba::math::chi2`
//! of v3.9.1).
#![allow(dead_code)]
// `!(x > 0.0)` is meant: it also rejects NaN, which `x <= 0.0` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use glam::{Vec2, Vec3};
use matte_brdf::registry::{ModelSpec, ParamSpec};
use matte_brdf::tabulated::{BrdfTable, TABLE_DELTA_PHI, TABLE_REFLECTANCE, TABLE_THETA};
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue};
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::f64::consts::PI;

#[path = "paths.rs"]
mod paths;
pub use matte_brdf::rng::Pcg32;
#[allow(unused_imports)] // the kernels' tests need neither; the crates above them do
pub use paths::*;

/// Test draws beyond the generator's own.
pub trait PcgExt {
    /// Uniform in [0, 1) with 53 random bits, from two draws.
    fn next_f64(&mut self) -> f64;
    /// Two `next_f32` draws.
    fn next_vec2(&mut self) -> Vec2;
    /// Uniform direction on the upper hemisphere.
    fn upper_hemisphere(&mut self) -> Vec3;
}

impl PcgExt for Pcg32 {
    fn next_f64(&mut self) -> f64 {
        ((self.next_u32() as u64) << 21 ^ (self.next_u32() as u64)) as f64 / (1u64 << 53) as f64
    }

    fn next_vec2(&mut self) -> Vec2 {
        let x = self.next_f32();
        Vec2::new(x, self.next_f32())
    }

    fn upper_hemisphere(&mut self) -> Vec3 {
        let z = self.next_f32();
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = 2.0 * std::f32::consts::PI * self.next_f32();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}

/// A model from `(name, value)` pairs written as in a scene (the catalogue's, the SPECs'
/// examples; [`ParamValue::parse`]), panicking on rejection (test inputs are valid).
pub fn model(kind: &str, params: &[(&str, &str)]) -> DiffuseModel {
    let values: Vec<(&str, ParamValue)> = params.iter().map(|(n, v)| (*n, ParamValue::parse(v))).collect();
    DiffuseModel::with(kind, &values).unwrap_or_else(|e| panic!("{kind} {params:?}: {e}"))
}

/// Every registered model that builds from its defaults, at its defaults and at each of its
/// declared examples (the set the plugin tests run too), plus low and high roughness and each
/// option of the models here.
pub fn catalogue() -> Vec<(String, DiffuseModel)> {
    let mut cfgs: Vec<(&str, &[(&str, &str)])> = Vec::new();
    // Every model that builds from its defaults (`tabulated_brdf` needs a table: its own tests).
    for spec in models_from_defaults() {
        cfgs.push((spec.name, &[]));
        cfgs.extend(spec.examples.iter().map(|e| (spec.name, *e)));
    }
    cfgs.extend_from_slice(&[
        ("oren_nayar", &[("sigma", "0.1")][..]),
        ("oren_nayar", &[("sigma", "1.0")]),
        ("oren_nayar", &[("sigma", "0.1"), ("model", "full")]),
        ("oren_nayar", &[("sigma", "1.0"), ("model", "full")]),
        ("eon", &[("roughness", "0.05")]),
        ("wolff", &[("int_ior", "2.4"), ("normalization", "normal")]),
        ("wolff", &[("int_ior", "bk7"), ("ext_ior", "water"), ("normalization", "raw")]),
        ("ginneken", &[("roughness", "0.1")]),
        ("ginneken", &[("roughness", "0.8"), ("shadowing", "height_correlated")]),
    ]);
    cfgs.iter().map(|(k, p)| (format!("{k} {p:?}"), model(k, p))).collect()
}

/// Where the registry-wide sweeps put a numeric parameter: the ends of its lane clamp (the
/// values a kernel can see), an infinite end replaced by that of its fit range (where `matte
/// fit` searches it, within its valid range).
pub fn sweep_bounds(p: &ParamSpec) -> (f64, f64) {
    let (lo, hi) = p.lane_clamp;
    (if lo.is_finite() { lo } else { p.fit.0 }, if hi.is_finite() { hi } else { p.fit.1 })
}

/// Values of a numeric parameter strictly inside [`sweep_bounds`]: 10 %, 35 %, 60 % and 85 % of
/// the way from the lower end. A sweep keeps those its model accepts with the other parameters
/// (Wolff's `ext_ior` must not exceed `int_ior`).
pub fn inner_values(p: &ParamSpec) -> [f64; 4] {
    let (lo, hi) = sweep_bounds(p);
    [0.1, 0.35, 0.6, 0.85].map(|t| lo + t * (hi - lo))
}

/// Every registered model that builds from its defaults (a model with a file parameter,
/// `tabulated_brdf`, has its own tests).
pub fn models_from_defaults() -> impl Iterator<Item = &'static ModelSpec> {
    matte_brdf::MODELS.iter().copied().filter(|m| m.builds_from_defaults())
}

/// Mitsuba's `SphericalDomain`: (φ, −cos θ) ∈ [−π, π] × [−1, 1] to a direction.
fn map_forward(x: f64, y: f64) -> Vec3 {
    let cos_theta = -y;
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    Vec3::new((x.cos() * sin_theta) as f32, (x.sin() * sin_theta) as f32, cos_theta as f32)
}

fn map_backward(w: Vec3) -> (f64, f64) {
    ((w.y as f64).atan2(w.x as f64), -(w.z as f64))
}

pub struct Chi2Outcome {
    pub p_value: f64,
    pub statistic: f64,
    pub dof: usize,
}

/// Mitsuba's `ChiSquareTest` with its defaults (10^6 samples, res 101 → 50 × 101 cells, ires 4
/// trapezoid rule per cell, pooling below 5) for `bsdf.sample_direction` against `bsdf.pdf`
/// at incidence `wi`. Returns `Err` for the hard failures (sample outside the domain, sample
/// in a cell of zero expected count, pdf integrating to > 1.1).
pub fn chi2_sampling<B: DiffuseBrdf>(bsdf: &B, wi: Vec3, seed: u64) -> Result<Chi2Outcome, String> {
    chi2_sampling_ires(bsdf, wi, seed, 4)
}

/// [`chi2_sampling`] with `ires` trapezoid points per cell side (sharp lobes, such as a rough
/// dielectric's transmission squeezed by η², need more than Mitsuba's 4 for the expected
/// counts to be accurate at 10^6 samples).
#[allow(dead_code)]
pub fn chi2_sampling_ires<B: DiffuseBrdf>(bsdf: &B, wi: Vec3, seed: u64, ires: usize) -> Result<Chi2Outcome, String> {
    chi2_test(|u| bsdf.sample(wi, u, [0.5]).map(|s| (s.wo, s.weight[0])), |wo| bsdf.pdf(wi, wo), seed, ires)
}

/// Mitsuba's `ChiSquareTest` of `sample` (`u` → direction and a weight whose sign counts)
/// against `pdf`, with `ires` trapezoid points per cell side.
pub fn chi2_test(
    mut sample: impl FnMut(Vec2) -> Option<(Vec3, f32)>,
    pdf: impl Fn(Vec3) -> f32,
    seed: u64,
    ires: usize,
) -> Result<Chi2Outcome, String> {
    const SAMPLES: usize = 1_000_000;
    let (nx, ny) = (50usize, 101usize);
    let (x0, x1, y0, y1) = (-PI, PI, -1.0, 1.0);
    let mut hist = vec![0.0f64; nx * ny];
    let mut rng = Pcg32::new(seed, 0xda3e_39cb_94b9_5bdb);
    for _ in 0..SAMPLES {
        let u = rng.next_vec2();
        let Some((wo, weight)) = sample(u) else { continue };
        if !(weight > 0.0) {
            continue; // Mitsuba's BSDFAdapter gives zero-weight samples no histogram mass
        }
        if (wo.length() - 1.0).abs() > 1e-3 {
            return Err(format!("sample {wo:?} is not a unit vector"));
        }
        let (x, y) = map_backward(wo);
        let ix = (((x - x0) / (x1 - x0) * nx as f64) as isize).clamp(0, nx as isize - 1) as usize;
        let iy = (((y - y0) / (y1 - y0) * ny as f64) as isize).clamp(0, ny as isize - 1) as usize;
        hist[iy * nx + ix] += 1.0;
    }
    // Expected counts: pdf integrated over each cell (trapezoid rule, as chi2.py).
    let (cw, ch) = ((x1 - x0) / nx as f64, (y1 - y0) / ny as f64);
    let (sx, sy) = (cw / (ires - 1) as f64, ch / (ires - 1) as f64);
    let mut expected = vec![0.0f64; nx * ny];
    for cy in 0..ny {
        for cx in 0..nx {
            let mut sum = 0.0;
            for j in 0..ires {
                for i in 0..ires {
                    let x = x0 + cx as f64 * cw + (i as f64 + 1e-4) * (1.0 - 2e-4) * sx;
                    let y = y0 + cy as f64 * ch + (j as f64 + 1e-4) * (1.0 - 2e-4) * sy;
                    let w = if i == 0 || i == ires - 1 { 0.5 } else { 1.0 }
                        * if j == 0 || j == ires - 1 { 0.5 } else { 1.0 };
                    let density = pdf(map_forward(x, y)) as f64;
                    if density < 0.0 || !density.is_finite() {
                        return Err(format!("pdf {density} at ({x}, {y})"));
                    }
                    sum += w * density;
                }
            }
            expected[cy * nx + cx] = sum * sx * sy * SAMPLES as f64;
        }
    }
    let pdf_sum: f64 = expected.iter().sum::<f64>() / SAMPLES as f64;
    if pdf_sum > 1.1 {
        return Err(format!("pdf integrates to {pdf_sum}"));
    }
    let mut order: Vec<usize> = (0..nx * ny).collect();
    order.sort_by(|&a, &b| expected[a].total_cmp(&expected[b]));
    if order.iter().any(|&k| expected[k] == 0.0 && hist[k] != 0.0) {
        return Err("samples in a cell with expected frequency 0".into());
    }
    // mitsuba::math::chi2 with pool threshold 5.
    let (mut chsq, mut pooled_obs, mut pooled_exp, mut dof) = (0.0, 0.0, 0.0, 0usize);
    for &k in &order {
        let (o, e) = (hist[k], expected[k]);
        if e == 0.0 && o == 0.0 {
            continue;
        }
        if e < 5.0 {
            pooled_obs += o;
            pooled_exp += e;
            if pooled_exp > 5.0 {
                chsq += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
                pooled_obs = 0.0;
                pooled_exp = 0.0;
                dof += 1;
            }
        } else {
            chsq += (o - e) * (o - e) / e;
            dof += 1;
        }
    }
    let dof = dof.saturating_sub(1);
    if dof < 1 {
        return Err("too few degrees of freedom".into());
    }
    let p_value = ChiSquared::new(dof as f64).map_err(|e| e.to_string())?.sf(chsq);
    Ok(Chi2Outcome { p_value, statistic: chsq, dof })
}

/// Šidák-corrected significance level for `test_count` tests at overall level 0.01.
pub fn sidak(test_count: usize) -> f64 {
    1.0 - (1.0 - 0.01f64).powf(1.0 / test_count as f64)
}

/// The direction at zenith `theta` and azimuth `phi` (radians).
pub fn direction(theta: f64, phi: f64) -> Vec3 {
    Vec3::new((theta.sin() * phi.cos()) as f32, (theta.sin() * phi.sin()) as f32, theta.cos() as f32)
}

/// `model` sampled on the ground-truth tables' grid.
pub fn table_of(m: &DiffuseModel) -> BrdfTable {
    BrdfTable::from_fn(
        "test",
        TABLE_THETA.to_vec(),
        TABLE_DELTA_PHI.to_vec(),
        TABLE_REFLECTANCE.to_vec(),
        |ti, to, dp, rho| m.eval(direction(ti, 0.0), direction(to, dp), [rho as f32])[0] as f64,
    )
    .unwrap()
}
