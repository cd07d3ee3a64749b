//! The 8-wide `Real` (`matte_brdf::simd::F32x8`) against the f32 one, lane by lane: every
//! model's eval, eval_pdf and sample, and each primitive operation, must give the same bits in
//! lane i as f32 gives for lane i's inputs (tolerance 0 ulp: the operations are the same IEEE
//! operations, rust/brdf/src/simd.rs), except that +0 and −0 count as equal: where every lane is
//! below the horizon the f32 path returns early with +0, while the branch-free wide path (like
//! the traced one) computes `0 · cos θo` = −0 for a negative cosine. The oracle is the f32 instantiation of the same generic
//! code, which the other kernel tests check against closed forms and references.

use crate::common::{models_from_defaults, sweep_bounds};
use glam::{Vec2, Vec3};
use matte_brdf::LaneKernel;
use matte_brdf::kernel;
use matte_brdf::real::Real;
use matte_brdf::simd::F32x8;
use matte_brdf::wide::direction_pairs;
use matte_brdf::wide::{ModelPair, to_lanes};

/// Random upper-hemisphere pairs plus the cases kernels guard: below the horizon, exactly on
/// it, grazing, normal incidence, coincident and opposite directions, signed zeros.
fn test_pairs() -> Vec<(Vec3, Vec3, Vec2)> {
    let mut pairs = direction_pairs(2048);
    let edge = [
        Vec3::Z,
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(-0.0, 1.0, 0.0),
        Vec3::new(1.0, 0.0, 1e-7).normalize(),
        Vec3::new(0.0, -1.0, 1e-4).normalize(),
        Vec3::new(0.6, 0.0, 0.8),
        Vec3::new(-0.6, 0.0, 0.8),
        Vec3::new(0.3, 0.4, -0.866),
        Vec3::new(-0.0, -0.0, 1.0),
    ];
    for (i, &a) in edge.iter().enumerate() {
        for (j, &b) in edge.iter().enumerate() {
            pairs.push((a, b, Vec2::new(i as f32 / 10.0, j as f32 / 10.0)));
        }
    }
    // Flip some random pairs below the horizon.
    for k in 0..64 {
        let (wi, wo, u) = pairs[k];
        pairs.push((Vec3::new(wi.x, wi.y, -wi.z), wo, u));
        pairs.push((wi, Vec3::new(wo.x, wo.y, -wo.z), u));
    }
    while !pairs.len().is_multiple_of(8) {
        pairs.push((Vec3::Z, Vec3::Z, Vec2::ZERO));
    }
    pairs
}

fn lanes(f: impl Fn(usize) -> f32) -> F32x8 {
    F32x8::new(std::array::from_fn(f))
}

fn assert_same(what: &str, lane: usize, wide: f32, scalar: f32) {
    assert!(
        wide.to_bits() == scalar.to_bits() || (wide == 0.0 && scalar == 0.0) || (wide.is_nan() && scalar.is_nan()),
        "{what}, lane {lane}: 8-wide {wide:e} ({:#x}) vs f32 {scalar:e} ({:#x})",
        wide.to_bits(),
        scalar.to_bits()
    );
}

const RHO: [f32; 3] = [0.8, 0.5, 0.2];

fn check_model(name: &str, scalar: &LaneKernel<'_, f32>, wide: &LaneKernel<'_, F32x8>, pairs: &[(Vec3, Vec3, Vec2)]) {
    let rho8 = RHO.map(F32x8::splat);
    for (chunk, (wi8, wo8)) in
        pairs.chunks_exact(8).zip(to_lanes(&pairs.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>()))
    {
        let f8 = kernel::eval(wide, wi8, wo8, rho8);
        let (fc8, pdf8) = kernel::eval_cos_pdf(wide, wi8, wo8, rho8);
        let (u1, u2) = (lanes(|i| chunk[i].2.x), lanes(|i| chunk[i].2.y));
        let (swo8, sw8, spdf8) = kernel::sample(wide, wi8, u1, u2, rho8);
        for (i, &(wi, wo, u)) in chunk.iter().enumerate() {
            let ctx = |what: &str| format!("{name} {what} wi={wi:?} wo={wo:?}");
            let f = kernel::eval(scalar, wi.into(), wo.into(), RHO);
            let (fc, pdf) = kernel::eval_cos_pdf(scalar, wi.into(), wo.into(), RHO);
            let (swo, sw, spdf) = kernel::sample(scalar, wi.into(), u.x, u.y, RHO);
            for c in 0..3 {
                assert_same(&ctx("eval"), i, f8[c].lane(i), f[c]);
                assert_same(&ctx("eval_pdf f"), i, fc8[c].lane(i), fc[c]);
                assert_same(&ctx("sample weight"), i, sw8[c].lane(i), sw[c]);
            }
            assert_same(&ctx("eval_pdf pdf"), i, pdf8.lane(i), pdf);
            // The scalar sample returns early (zero direction) when wi is below; the wide one
            // draws for the other lanes, so only the weight and pdf agree there.
            if wi.z > 0.0 {
                for (a, b) in [(swo8.x, swo.x), (swo8.y, swo.y), (swo8.z, swo.z)] {
                    assert_same(&ctx("sample wo"), i, a.lane(i), b);
                }
            }
            assert_same(&ctx("sample pdf"), i, spdf8.lane(i), spdf);
        }
    }
}

#[test]
fn every_model_evaluates_lane_by_lane_as_f32() {
    let pairs = test_pairs();
    // Every model at its defaults (`tabulated_brdf` needs a table: tabulated_brdf.rs checks its kernel).
    for model in models_from_defaults().map(|m| m.name) {
        let pair = ModelPair::new(model).expect("every model has a wide kernel");
        check_model(model, &pair.scalar(), &pair.wide(), &pairs);
    }
}

/// Parameters that differ per lane (textured σ, r, n, …): lane i of the wide kernel built from
/// eight values of one numeric parameter (the others at their defaults) is the f32 kernel built
/// from value i. Every numeric parameter of every registered model, at eight values across
/// [`sweep_bounds`]: its lower end, just above it, and on to its upper end.
#[test]
fn per_lane_parameters_match_one_f32_kernel_per_lane() {
    let pairs = test_pairs();
    let mut checked = 0;
    for spec in models_from_defaults() {
        let pair = ModelPair::new(spec.name).expect("every model has a wide kernel");
        for (k, param) in spec.numeric().enumerate() {
            let (lo, hi) = sweep_bounds(param);
            let p: [f32; 8] = [0.0, 1e-4, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0].map(|t: f64| (lo + t * (hi - lo)) as f32);
            let wide = pair.kernel_with(|j, d| if j == k { F32x8::new(p) } else { F32x8::splat(d) });
            let scalars: Vec<LaneKernel<'_, f32>> =
                (0..8).map(|i| pair.kernel_with(|j, d| if j == k { p[i] } else { d })).collect();
            let rho8 = RHO.map(F32x8::splat);
            for (chunk, (wi8, wo8)) in
                pairs.chunks_exact(8).zip(to_lanes(&pairs.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>()))
            {
                let f8 = kernel::eval(&wide, wi8, wo8, rho8);
                for (i, &(wi, wo, _)) in chunk.iter().enumerate() {
                    let f = kernel::eval(&scalars[i], wi.into(), wo.into(), RHO);
                    for c in 0..3 {
                        let what = format!("{} {} = {} wi={wi:?} wo={wo:?}", spec.name, param.name, p[i]);
                        assert_same(&what, i, f8[c].lane(i), f[c]);
                    }
                }
            }
            checked += 1;
        }
    }
    assert!(checked >= 5, "only {checked} numeric parameters");
}

/// Each primitive on special values (NaN, ±0, ±∞, ties, denormals) as f32 computes it.
#[test]
fn primitive_operations_match_f32_on_special_values() {
    let specials = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        -2.5,
        1e-40,
        -1e-40,
        3.4e38,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        0.1,
        7.75,
        -1e-7,
        16777217.0,
    ];
    for (ka, ca) in specials.chunks_exact(8).enumerate() {
        for (kb, cb) in specials.chunks_exact(8).enumerate() {
            for shift in 0..8 {
                let a: [f32; 8] = std::array::from_fn(|i| ca[i]);
                let b: [f32; 8] = std::array::from_fn(|i| cb[(i + shift) % 8]);
                let (a8, b8) = (F32x8::new(a), F32x8::new(b));
                let ctx = |op: &str| format!("{op} (chunks {ka},{kb}, shift {shift})");
                for i in 0..8 {
                    let (x, y) = (a[i], b[i]);
                    assert_same(&ctx("add"), i, (a8 + b8).lane(i), x + y);
                    assert_same(&ctx("sub"), i, (a8 - b8).lane(i), x - y);
                    assert_same(&ctx("mul"), i, (a8 * b8).lane(i), x * y);
                    assert_same(&ctx("div"), i, (a8 / b8).lane(i), x / y);
                    assert_same(&ctx("neg"), i, (-a8).lane(i), -x);
                    assert_same(&ctx("min"), i, a8.min(b8).lane(i), Real::min(x, y));
                    assert_same(&ctx("max"), i, a8.max(b8).lane(i), Real::max(x, y));
                    assert_same(&ctx("fma"), i, a8.fma(b8, a8).lane(i), Real::fma(x, y, x));
                    assert_same(&ctx("sqrt"), i, a8.sqrt().lane(i), x.sqrt());
                    assert_same(&ctx("abs"), i, Real::abs(a8).lane(i), x.abs());
                    assert_same(&ctx("floor"), i, Real::floor(a8).lane(i), x.floor());
                    assert_same(&ctx("safe_sqrt"), i, a8.safe_sqrt().lane(i), x.safe_sqrt());
                    assert_same(&ctx("clamp"), i, a8.clamp_to(-1.0, 1.0).lane(i), x.clamp_to(-1.0, 1.0));
                    assert_eq!(a8.lt(b8).lane(i), x < y, "{}", ctx("lt"));
                    assert_eq!(a8.le(b8).lane(i), x <= y, "{}", ctx("le"));
                    assert_eq!(a8.gt(b8).lane(i), x > y, "{}", ctx("gt"));
                    assert_eq!(a8.eq(b8).lane(i), x == y, "{}", ctx("eq"));
                    let m = a8.lt(b8) | !a8.eq(b8);
                    assert_eq!(m.lane(i), x < y || x != y, "{}", ctx("mask or/not"));
                    assert_same(&ctx("select"), i, F32x8::select(m & a8.gt(b8), a8, b8).lane(i), {
                        if (x < y || x != y) && x > y { x } else { y }
                    });
                    let (s8, c8) = a8.sincos();
                    let (s, c) = x.sincos();
                    assert_same(&ctx("sin"), i, s8.lane(i), s);
                    assert_same(&ctx("cos"), i, c8.lane(i), c);
                }
            }
        }
    }
    assert!(F32x8::none(F32x8::splat(1.0).lt(F32x8::splat(0.0))));
    assert!(!F32x8::none(F32x8::new([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]).lt(F32x8::splat(0.0))));
    assert_eq!(F32x8::mask(true).bits(), 0xff);
    assert_eq!(F32x8::mask(false).bits(), 0);
}

/// Table lookups: lane i reads what f32 reads for its index, the clamp at the end included.
#[test]
fn gather_reads_each_lanes_node() {
    let data: [f32; 13] = std::array::from_fn(|i| i as f32 * 1.5 - 3.0);
    let nodes = matte_brdf::real::Nodes::new(&data);
    let idx = [0.0, 1.0, 2.0, 5.0, 11.0, 12.0, 13.0, 40.0];
    for offset in [0, 1, 3] {
        let g = F32x8::gather(nodes, F32x8::new(idx), offset);
        for (i, &x) in idx.iter().enumerate() {
            assert_same(&format!("gather offset {offset}"), i, g.lane(i), f32::gather(nodes, x, offset));
        }
    }
}
