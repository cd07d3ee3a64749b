//! Every model's kernel twice, in `f32` and in the 8-wide [`F32x8`], with its constants built
//! by the same generic constructor from the same f32 parameter (so lane `i` of the wide
//! kernel is the f32 kernel, operation for operation). The criterion benchmark
//! (`benches/kernels.rs`, group `wide`) times both; `tests/simd_kernels.rs` compares them lane
//! by lane.

use crate::brdf::eon::EonKernel;
use crate::brdf::ginneken::shadowing::Shadowing;
use crate::brdf::ginneken::{Ginneken, GinnekenKernel};
use crate::brdf::kernel::{self, Kernel};
use crate::brdf::oren_nayar::{OrenNayarKernel, OrenNayarModel};
use crate::brdf::real::{Real, V3};
use crate::brdf::simd::F32x8;
use crate::brdf::wolff::{WolffKernel, WolffNormalization};
use crate::brdf::{Lambert, RoughDiffuse};
use std::sync::Arc;

/// One model's kernel in any [`Real`] whose tables are [`crate::brdf::real::Nodes`].
pub enum AnyKernel<'t, T: Real> {
    Lambert(Lambert),
    OrenNayar(OrenNayarKernel<T>),
    Eon(EonKernel<T>),
    Wolff(WolffKernel<T>),
    Ginneken(GinnekenKernel<'t, T>),
}

impl<'t, T: Real> Kernel<T> for AnyKernel<'t, T> {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        match self {
            AnyKernel::Lambert(k) => k.reduced_f(wi, wo, rho),
            AnyKernel::OrenNayar(k) => k.reduced_f(wi, wo, rho),
            AnyKernel::Eon(k) => k.reduced_f(wi, wo, rho),
            AnyKernel::Wolff(k) => k.reduced_f(wi, wo, rho),
            AnyKernel::Ginneken(k) => k.reduced_f(wi, wo, rho),
        }
    }
}

/// A model at its default parameters (or `param`, its numeric parameter), in both widths.
pub struct ModelPair {
    pub model: &'static str,
    /// van Ginneken's tables (shared by both kernels).
    ginneken: Option<Arc<Ginneken>>,
    kind: Kind,
}

#[derive(Clone, Copy)]
enum Kind {
    Lambert,
    OrenNayar(f32, OrenNayarModel),
    Eon(f32),
    Wolff(f32, WolffNormalization),
    Ginneken,
}

impl ModelPair {
    /// `model` (one of [`crate::brdf::BSDF_TYPES`]) at its default parameters.
    pub fn new(model: &'static str) -> Option<Self> {
        let (kind, ginneken) = match model {
            "lambert" => (Kind::Lambert, None),
            "oren_nayar" => (Kind::OrenNayar(0.3, OrenNayarModel::Qualitative), None),
            "roughdiffuse" => (
                Kind::OrenNayar(RoughDiffuse::sigma_of_alpha(RoughDiffuse::DEFAULT_ALPHA) as f32, OrenNayarModel::Full),
                None,
            ),
            "eon" => (Kind::Eon(0.3), None),
            "wolff" => (Kind::Wolff(1.4, WolffNormalization::Physical), None),
            "ginneken" => {
                (Kind::Ginneken, Some(Arc::new(Ginneken::new(0.3, Shadowing::VanGinneken).expect("valid roughness"))))
            }
            _ => return None,
        };
        Some(ModelPair { model, ginneken, kind })
    }

    /// The kernel in `T`, its constants from `param` (the model's numeric parameter per lane;
    /// ignored by Lambert and van Ginneken, whose table is for one roughness).
    pub fn kernel_with<T: for<'a> Real<Table<'a> = crate::brdf::real::Nodes<'a>>>(
        &self,
        param: impl Fn(f32) -> T,
    ) -> AnyKernel<'_, T> {
        match self.kind {
            Kind::Lambert => AnyKernel::Lambert(Lambert),
            Kind::OrenNayar(s, m) => AnyKernel::OrenNayar(OrenNayarKernel::new(param(s), m)),
            Kind::Eon(r) => AnyKernel::Eon(EonKernel::new(param(r))),
            Kind::Wolff(n, norm) => AnyKernel::Wolff(WolffKernel::new(param(n), norm)),
            Kind::Ginneken => {
                let k = self.ginneken.as_ref().expect("built with the model").kernel();
                AnyKernel::Ginneken(GinnekenKernel {
                    slope: k.slope,
                    mu_lambda: k.mu_lambda,
                    roughness_derivative: None,
                    shadowing: k.shadowing,
                })
            }
        }
    }

    /// The f32 kernel at the default parameter.
    pub fn scalar(&self) -> AnyKernel<'_, f32> {
        self.kernel_with(|p| p)
    }

    /// The 8-wide kernel at the default parameter (every lane the same).
    pub fn wide(&self) -> AnyKernel<'_, F32x8> {
        self.kernel_with(F32x8::splat)
    }
}

/// `f` (RGB) of eight direction pairs, 8-wide.
#[inline(always)]
pub fn eval_wide(k: &AnyKernel<'_, F32x8>, wi: V3<F32x8>, wo: V3<F32x8>, rho: [F32x8; 3]) -> [F32x8; 3] {
    kernel::eval(k, wi, wo, rho)
}

/// `f` (RGB) of one direction pair, f32.
#[inline(always)]
pub fn eval_scalar(k: &AnyKernel<'_, f32>, wi: V3<f32>, wo: V3<f32>, rho: [f32; 3]) -> [f32; 3] {
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
