//! ns per eval and per sample for each model (default parameters, one reflectance channel
//! and RGB), over 4096 precomputed random direction pairs cycled so that branch prediction
//! and caches see renderer-like variety; and (group `wide`) the same RGB evals through the
//! generic kernels in f32, one pair per call, against the 8-wide `F32x8`, eight pairs per
//! call (throughput in pairs either way). Run: `cargo bench --bench kernels`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use matte_brdf::simd::F32x8;
use matte_brdf::wide::direction_pairs;
use matte_brdf::wide::{ModelPair, eval_scalar, eval_wide, to_lanes};
use matte_brdf::{BSDF_TYPES, DiffuseBrdf, DiffuseModel, Params};
use std::hint::black_box;

fn kernels(c: &mut Criterion) {
    let data = direction_pairs(4096);
    let mut group = c.benchmark_group("kernel");
    group.throughput(Throughput::Elements(data.len() as u64));
    for kind in BSDF_TYPES {
        let bsdf = DiffuseModel::from_params(kind, Params::new()).unwrap();
        group.bench_function(format!("{kind}/eval"), |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for (wi, wo, _) in &data {
                    acc += bsdf.eval(black_box(*wi), black_box(*wo), [0.5])[0];
                }
                black_box(acc)
            })
        });
        group.bench_function(format!("{kind}/eval_rgb"), |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for (wi, wo, _) in &data {
                    acc += bsdf.eval(black_box(*wi), black_box(*wo), [0.8, 0.5, 0.2])[1];
                }
                black_box(acc)
            })
        });
        group.bench_function(format!("{kind}/sample"), |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for (wi, _, u) in &data {
                    if let Some(s) = bsdf.sample(black_box(*wi), black_box(*u), [0.5]) {
                        acc += s.weight[0];
                    }
                }
                black_box(acc)
            })
        });
    }
    group.finish();
}

fn wide(c: &mut Criterion) {
    let data = direction_pairs(4096);
    let pairs: Vec<_> = data.iter().map(|p| (p.0, p.1)).collect();
    let lanes = to_lanes(&pairs);
    let mut group = c.benchmark_group("wide");
    group.throughput(Throughput::Elements(pairs.len() as u64));
    for kind in BSDF_TYPES {
        let model = ModelPair::new(kind).expect("every model has a wide kernel");
        let (scalar, wide) = (model.scalar(), model.wide());
        group.bench_function(format!("{kind}/f32"), |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for (wi, wo) in &pairs {
                    acc += eval_scalar(&scalar, black_box(*wi).into(), black_box(*wo).into(), [0.8, 0.5, 0.2])[1];
                }
                black_box(acc)
            })
        });
        let rho = [0.8, 0.5, 0.2].map(F32x8::splat);
        group.bench_function(format!("{kind}/f32x8"), |b| {
            b.iter(|| {
                let mut acc = F32x8::splat(0.0);
                for (wi, wo) in &lanes {
                    acc = acc + eval_wide(&wide, black_box(*wi), black_box(*wo), rho)[1];
                }
                black_box(acc)
            })
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(2)).warm_up_time(std::time::Duration::from_millis(500));
    targets = kernels, wide
}
criterion_main!(benches);
