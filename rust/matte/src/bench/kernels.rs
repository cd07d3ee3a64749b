//! Kernel speed: ns per `eval` (RGB reflectance) of every model, over a fixed set of random
//! direction pairs cycled so that branch prediction and caches see renderer-like variety.
//! The same pairs feed the criterion benchmark (`benches/kernels.rs`).

use glam::Vec3;
use matte_brdf::wide::direction_pairs;
use matte_brdf::{DiffuseBrdf, DiffuseModel, Params};
use std::hint::black_box;
use std::time::Instant;

/// One model's eval speed.
#[derive(Clone, Debug)]
pub struct KernelTime {
    pub model: &'static str,
    pub ns_per_eval: f64,
}

/// Best-of-`repeats` ns per RGB eval for every model at its default parameters (the models
/// that build from their defaults: not `tabulated_brdf`).
pub fn time_kernels(repeats: u32) -> Vec<KernelTime> {
    let data = direction_pairs(4096);
    matte_brdf::default_models()
        .map(|model| {
            let bsdf = DiffuseModel::from_params(model, Params::new()).expect("default parameters are valid");
            let pass = || {
                let t = Instant::now();
                let mut acc = 0.0f32;
                for _ in 0..64 {
                    for (wi, wo, _) in &data {
                        acc += bsdf.eval(black_box(*wi), black_box(*wo), [0.8, 0.5, 0.2])[1];
                    }
                }
                black_box(acc);
                t.elapsed().as_secs_f64() * 1e9 / (64 * data.len()) as f64
            };
            pass(); // warm-up (van Ginneken's table is built on first use)
            let ns = (0..repeats.max(1)).map(|_| pass()).fold(f64::INFINITY, f64::min);
            KernelTime { model, ns_per_eval: ns }
        })
        .collect()
}

/// One model's generic kernel in f32 and 8-wide: ns per RGB eval of one direction pair.
#[derive(Clone, Debug)]
pub struct WideKernelTime {
    pub model: &'static str,
    pub f32_ns: f64,
    pub f32x8_ns: f64,
}

/// Best-of-`repeats` ns per RGB eval and pair for every model, f32 against
/// [`matte_brdf::simd::F32x8`] (`matte_brdf::wide`: same constructors, same pairs). The
/// two take turns within each repeat, so that the machine's load hits them alike.
pub fn time_wide_kernels(repeats: u32) -> Vec<WideKernelTime> {
    use matte_brdf::simd::F32x8;
    use matte_brdf::wide::{ModelPair, eval_scalar, eval_wide, to_lanes};
    let pairs: Vec<(Vec3, Vec3)> = direction_pairs(4096).into_iter().map(|p| (p.0, p.1)).collect();
    let lanes = to_lanes(&pairs);
    matte_brdf::default_models()
        .filter_map(|model| {
            let m = ModelPair::new(model)?;
            let (scalar, wide) = (m.scalar(), m.wide());
            let per_pair = |t: Instant| t.elapsed().as_secs_f64() * 1e9 / (64 * pairs.len()) as f64;
            let f32_pass = || {
                let t = Instant::now();
                let mut acc = 0.0f32;
                for _ in 0..64 {
                    for (wi, wo) in &pairs {
                        acc += eval_scalar(&scalar, black_box(*wi).into(), black_box(*wo).into(), [0.8, 0.5, 0.2])[1];
                    }
                }
                black_box(acc);
                per_pair(t)
            };
            let rho = [0.8, 0.5, 0.2].map(F32x8::splat);
            let wide_pass = || {
                let t = Instant::now();
                let mut acc = F32x8::splat(0.0);
                for _ in 0..64 {
                    for (wi, wo) in &lanes {
                        acc = acc + eval_wide(&wide, black_box(*wi), black_box(*wo), rho)[1];
                    }
                }
                black_box(acc);
                per_pair(t)
            };
            let (mut f32_ns, mut f32x8_ns) = (f64::INFINITY, f64::INFINITY);
            for _ in 0..repeats.max(1) + 1 {
                f32_ns = f32_ns.min(f32_pass());
                f32x8_ns = f32x8_ns.min(wide_pass());
            }
            Some(WideKernelTime { model, f32_ns, f32x8_ns })
        })
        .collect()
}
