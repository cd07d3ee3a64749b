//! Lambert: `f = ρ/π` (Lambert 1760). Must agree with Mitsuba's built-in `diffuse` to float
//! precision, including its sampling routine and its sampling weight `ρ`.

use crate::kernel::Kernel;
use crate::params::{ParamError, ParamValue};
use crate::real::{Real, V3};
use crate::registry::{Evaluation, Gradients, KernelBrdf, ModelSpec, NoValues, Registered, Values, parameter_values};

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Lambert;

impl<T: Real> Kernel<T> for Lambert {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, _wi: V3<T>, _wo: V3<T>, rho: [T; N]) -> [T; N] {
        rho
    }
}


impl KernelBrdf for Lambert {
    fn f32_kernel(&self) -> impl Kernel<f32> + '_ {
        *self
    }

    fn closed_form_albedo(&self, _cos_theta_i: f64, rho: f32) -> Option<f64> {
        Some(rho as f64)
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
        parameter_values!()
    }

    type Parameters<T: Real> = NoValues;
    type Coefficients<T: Real> = NoValues;

    fn constant_coefficients<T: Real>(&self, _: NoValues, _: Gradients) -> NoValues {
        NoValues
    }

    fn kernel_from<'t, T: Real + 't>(&self, _: NoValues, _: &[T::Table<'t>], _: Evaluation) -> Option<Lambert> {
        Some(Lambert)
    }
}
