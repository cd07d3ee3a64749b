//! [`KernelBrdf`]: a BRDF given by an f32 kernel, and the blanket [`DiffuseBrdf`]
//! implementation that evaluates, samples and integrates it.

use crate::diffuse_brdf::{Albedo, AlbedoMethod, BrdfSample, DiffuseBrdf, albedo_by_quadrature};
use crate::kernel::{self, Kernel};
use glam::{Vec2, Vec3};

/// A BRDF given by an f32 [`Kernel`]: every registered model, and matte's tabulated BRDF
/// (`crate::tabulated::Tabulated`). Each is a [`DiffuseBrdf`] through the blanket
/// implementation below.
pub trait KernelBrdf {
    /// The kernel in f32 with its constants: what every [`DiffuseBrdf`] method runs.
    fn f32_kernel(&self) -> impl Kernel<f32> + '_;

    /// The directional albedo for a grey reflectance `rho` in closed form, where the model has
    /// one; `None` (the default) lets [`DiffuseBrdf::albedo`] integrate numerically. Called
    /// with `cos_theta_i > 0` only (the albedo is 0 below the surface).
    fn closed_form_albedo(&self, cos_theta_i: f64, rho: f32) -> Option<f64> {
        let _ = (cos_theta_i, rho);
        None
    }
}

/// Every [`KernelBrdf`] is a [`DiffuseBrdf`] through its f32 kernel: evaluation, density and
/// sampling are [`kernel`]'s, the albedo the model's closed form or quadrature.
impl<M: KernelBrdf> DiffuseBrdf for M {
    /// `inline(always)`: with the full Oren–Nayar body the function exceeds the inliner's
    /// threshold, and a call would cost the default (qualitative) model a third of its time.
    #[inline(always)]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        kernel::eval(&self.f32_kernel(), wi.into(), wo.into(), reflectance)
    }

    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        kernel::pdf(&self.f32_kernel(), wi.into(), wo.into())
    }

    #[inline]
    fn sample<const N: usize>(&self, wi: Vec3, u: Vec2, reflectance: [f32; N]) -> Option<BrdfSample<N>> {
        BrdfSample::from_kernel(kernel::sample(&self.f32_kernel(), wi.into(), u.x, u.y, reflectance))
    }

    fn albedo(&self, cos_theta_i: f64, reflectance: f32) -> Albedo {
        if cos_theta_i <= 0.0 {
            return Albedo { value: 0.0, method: AlbedoMethod::ClosedForm };
        }
        match self.closed_form_albedo(cos_theta_i, reflectance) {
            Some(value) => Albedo { value, method: AlbedoMethod::ClosedForm },
            None => {
                Albedo { value: albedo_by_quadrature(self, cos_theta_i, reflectance), method: AlbedoMethod::Quadrature }
            }
        }
    }
}
