//! Every model's kernel twice, in `f32` and in the 8-wide [`F32x8`], with its constants built
//! by the same generic constructor from the same f32 parameter (so lane `i` of the wide
//! kernel is the f32 kernel, operation for operation). The criterion benchmark
//! (`benches/kernels.rs`, group `wide`) and `matte bench` time both, on the same
//! [`direction_pairs`]; `tests/kernels/simd_kernels.rs` compares them lane by lane.

use crate::kernel;
use crate::real::{Nodes, Real, V3};
use crate::registry::{Evaluation, Flat, Gradients, Registered};
use crate::simd::F32x8;
use crate::{DiffuseModel, LaneKernel, ParamValue, Params, dispatch};
use glam::{Vec2, Vec3};

/// `n` deterministic (wi, wo, u) triples: directions uniform on the upper hemisphere, u
/// uniform in [0,1)².
pub fn direction_pairs(n: usize) -> Vec<(Vec3, Vec3, Vec2)> {
    // xorshift64*: deterministic, no dependency
    let mut s = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = || {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        (s.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40) as f32 / (1u64 << 24) as f32
    };
    let dir = |a: f32, b: f32| {
        let z = a;
        let r = (1.0 - z * z).sqrt();
        let p = 2.0 * std::f32::consts::PI * b;
        Vec3::new(r * p.cos(), r * p.sin(), z)
    };
    (0..n).map(|_| (dir(next(), next()), dir(next(), next()), Vec2::new(next(), next()))).collect()
}

/// A model at its default parameters, whose kernel is built in both widths.
pub struct ModelPair {
    pub model: &'static str,
    bsdf: DiffuseModel,
}

impl ModelPair {
    /// `model` (one of [`crate::BSDF_TYPES`]) at its default parameters.
    pub fn new(model: &'static str) -> Option<Self> {
        Some(ModelPair { model, bsdf: DiffuseModel::from_params(model, Params::new()).ok()? })
    }

    /// The kernel in `T`, its constants from `param(k, default)`: the value of the model's
    /// `k`-th numeric parameter, given its default (van Ginneken's tables are those of its
    /// default roughness).
    pub fn kernel_with<T: for<'a> Real<Table<'a> = Nodes<'a>>>(
        &self,
        param: impl Fn(usize, f32) -> T,
    ) -> LaneKernel<'_, T> {
        let defaults = self.bsdf.parameters().into_iter().filter_map(|(_, v)| match v {
            ParamValue::Number(x) => Some(x as f32),
            _ => None,
        });
        let values: Vec<T> = defaults.enumerate().map(|(k, d)| param(k, d)).collect();
        dispatch!(&self.bsdf, m => {
            let tables: Vec<Nodes<'_>> =
                m.tables(Evaluation::Constant).into_iter().filter_map(Nodes::from_slice).collect();
            Flat::from_flat(&values).and_then(|p| {
                m.kernel_from::<T>(m.constant_coefficients::<T>(p, Gradients::NotNeeded), &tables, Evaluation::Constant)
            })
        }, lane)
        .expect("a model's defaults give its kernel")
    }

    /// The f32 kernel at the default parameters.
    pub fn scalar(&self) -> LaneKernel<'_, f32> {
        self.kernel_with(|_, d| d)
    }

    /// The 8-wide kernel at the default parameters (every lane the same).
    pub fn wide(&self) -> LaneKernel<'_, F32x8> {
        self.kernel_with(|_, d| F32x8::splat(d))
    }
}

/// `f` (RGB) of eight direction pairs, 8-wide.
#[inline(always)]
pub fn eval_wide(k: &LaneKernel<'_, F32x8>, wi: V3<F32x8>, wo: V3<F32x8>, rho: [F32x8; 3]) -> [F32x8; 3] {
    kernel::eval(k, wi, wo, rho)
}

/// `f` (RGB) of one direction pair, f32.
#[inline(always)]
pub fn eval_scalar(k: &LaneKernel<'_, f32>, wi: V3<f32>, wo: V3<f32>, rho: [f32; 3]) -> [f32; 3] {
    kernel::eval(k, wi, wo, rho)
}

/// Groups of eight (wi, wo) pairs as lanes.
pub fn to_lanes(pairs: &[(glam::Vec3, glam::Vec3)]) -> Vec<(V3<F32x8>, V3<F32x8>)> {
    pairs
        .chunks_exact(8)
        .map(|c| {
            let lane = |f: &dyn Fn(usize) -> f32| F32x8::new(std::array::from_fn(f));
            (
                V3::new(lane(&|i| c[i].0.x), lane(&|i| c[i].0.y), lane(&|i| c[i].0.z)),
                V3::new(lane(&|i| c[i].1.x), lane(&|i| c[i].1.y), lane(&|i| c[i].1.z)),
            )
        })
        .collect()
}
