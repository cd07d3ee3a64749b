//! Lambert: `f = ρ/π` (Lambert 1760). Must agree with Mitsuba's built-in `diffuse` to float
//! precision, including its sampling routine and its sampling weight `ρ`.

use super::kernel::{self, Kernel};
use super::model::{Albedo, AlbedoMethod, BrdfSample, DiffuseBrdf};
use super::params::{ParamError, ParamValue};
use super::real::{Real, V3};
use super::registry::{ModelSpec, Registered, Values};
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

impl Registered for Lambert {
    const SPEC: ModelSpec = ModelSpec {
        name: "lambert",
        label: "Lambert",
        summary: "`ρ/π`; matches Mitsuba's `diffuse`, sampling included",
        params: &[],
        examples: &[],
        in_study: true,
    };
    type Lane<'t, T: Real + 't> = Lambert;

    fn build(_: &Values) -> Result<Self, ParamError> {
        Ok(Lambert)
    }

    fn values(&self) -> Vec<ParamValue> {
        Vec::new()
    }

    fn constant_coefficients<T: Real>(&self, _: &[T], _: bool) -> Option<Vec<T>> {
        Some(Vec::new())
    }

    fn kernel_from<'t, T: Real + 't>(&self, _: &[T], _: &[T::Table<'t>], _: bool) -> Option<Lambert> {
        Some(Lambert)
    }
}
