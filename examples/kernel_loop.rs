use matte::brdf::{Bsdf, DiffuseBrdf, Params};
use std::hint::black_box;

#[inline(never)]
fn hot_loop(bsdf: &Bsdf, data: &[(glam::Vec3, glam::Vec3, glam::Vec2)]) -> f32 {
    let mut acc = 0.0f32;
    for _ in 0..16 {
        for (wi, wo, _) in data {
            acc += bsdf.eval(black_box(*wi), black_box(*wo), [0.8, 0.5, 0.2])[1];
        }
    }
    acc
}

fn main() {
    let model = std::env::args().nth(1).unwrap();
    let bsdf = Bsdf::from_params(&model, Params::new()).unwrap();
    let data = matte::bench::kernels::direction_pairs(4096);
    black_box(hot_loop(&bsdf, &data[..16]));
    let t = std::time::Instant::now();
    let mut best = f64::INFINITY;
    for _ in 0..20 {
        let t0 = std::time::Instant::now();
        black_box(hot_loop(&bsdf, &data));
        best = best.min(t0.elapsed().as_secs_f64() * 1e9 / (16.0 * 4096.0));
    }
    let _ = t;
    println!("{model} {best:.2} ns/eval");
}
