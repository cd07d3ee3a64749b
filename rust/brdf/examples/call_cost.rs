//! Instructions per call of a model's f32 `eval` or `sample` (RGB), for callgrind:
//!
//!     validation/experiments/call_cost.sh [MODEL ...]
//!
//! runs `cargo run --release -p matte-brdf --example call_cost -- MODEL eval|sample N` under
//! `valgrind --tool=callgrind --toggle-collect='call_cost::calls*'`, so that only the calls
//! count (not building the model's tables), and divides by N. The direction pairs are random
//! (cosine-ish in θ down to 0.06°, uniform in φ), the same for every model.

use glam::{Vec2, Vec3};
use matte_brdf::{DiffuseBrdf, DiffuseModel, Params};
use std::hint::black_box;

/// `n` direction pairs and sample points from a fixed linear congruential sequence.
fn inputs(n: usize) -> Vec<(Vec3, Vec3, Vec2)> {
    let mut state = 12345u64;
    let mut uniform = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 40) as f32) / (1u64 << 24) as f32
    };
    (0..n)
        .map(|_| {
            let mut direction = || {
                let (z, phi) = (uniform().max(1e-3), std::f32::consts::TAU * uniform());
                let s = (1.0 - z * z).sqrt();
                Vec3::new(s * phi.cos(), s * phi.sin(), z)
            };
            let (wi, wo) = (direction(), direction());
            (wi, wo, Vec2::new(uniform(), uniform()))
        })
        .collect()
}

/// The measured calls (callgrind counts only inside this function).
#[inline(never)]
fn calls(model: &DiffuseModel, inputs: &[(Vec3, Vec3, Vec2)], sample: bool) -> f32 {
    let mut sum = 0.0;
    for &(wi, wo, u) in inputs {
        sum += if sample {
            black_box(model.sample(black_box(wi), black_box(u), [0.5, 0.6, 0.7])).map_or(0.0, |s| s.weight[0])
        } else {
            black_box(model.eval(black_box(wi), black_box(wo), [0.5, 0.6, 0.7]))[0]
        };
    }
    sum
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let [_, name, what, n] = &args[..] else {
        eprintln!("usage: call_cost MODEL eval|sample N");
        std::process::exit(2);
    };
    let model = DiffuseModel::from_params(name, Params::new()).unwrap_or_else(|e| {
        eprintln!("call_cost: {name}: {e}");
        std::process::exit(2)
    });
    let n: usize = n.parse().unwrap_or_else(|_| {
        eprintln!("call_cost: N must be a count, not {n}");
        std::process::exit(2)
    });
    println!("{}", calls(&model, &inputs(n), what == "sample"));
}
