//! Lambert: `f = ρ/π` (Lambert 1760). Must agree with Mitsuba's built-in `diffuse` to float
//! precision, including its sampling routine and its sampling weight `ρ`.

use super::kernel::{self, Kernel};
use super::model::{Albedo, AlbedoMethod, BrdfSample, DiffuseBrdf};
use super::real::{Real, V3};
use glam::{Vec2, Vec3};

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Lambert;

impl<T: Real> Kernel<T> for Lambert {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, _wi: V3<T>, _wo: V3<T>, rho: [T; N]) -> [T; N] {
        rho
    }
}

impl DiffuseBrdf for Lambert {
    #[inline]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        kernel::eval(self, wi.into(), wo.into(), reflectance)
    }

    #[inline]
    fn sample<const N: usize>(&self, wi: Vec3, u: Vec2, reflectance: [f32; N]) -> Option<BrdfSample<N>> {
        BrdfSample::from_kernel(kernel::sample(self, wi.into(), u.x, u.y, reflectance))
    }

    fn albedo(&self, cos_theta_i: f64, reflectance: f32) -> Albedo {
        let value = if cos_theta_i > 0.0 { reflectance as f64 } else { 0.0 };
        Albedo { value, method: AlbedoMethod::ClosedForm }
    }
}
