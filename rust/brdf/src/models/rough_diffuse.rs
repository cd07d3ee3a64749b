//! Mitsuba 0.6's `roughdiffuse` (`src/bsdfs/roughdiffuse.cpp`): Oren–Nayar with the roughness
//! given as the RMS slope `alpha` of Mitsuba's microfacet models and converted to Oren–Nayar's
//! slope-angle standard deviation by `σ = α/√2` (0.6's conversion, "a perfect fit up to
//! extreme roughness values"). `use_fast_approx` (0.6 XML: `useFastApprox`) selects the
//! qualitative model; the default is the full one. Defaults as 0.6: α = 0.2, ρ = 0.5.
//! So that scenes written for Mitsuba 0.6 render with the rough diffuse model they asked for.

use crate::cltc::Sampling;
use crate::kernel::Kernel;
use super::oren_nayar::{OrenNayar, OrenNayarCoefficients, OrenNayarForm, OrenNayarKernel};
use crate::params::{ParamError, ParamValue};
use crate::real::Real;
use crate::registry::{
    Evaluation, Gradients, KernelBrdf, ModelSpec, ParamSpec, Range, Registered, Values, flat_values, param,
    parameter_values,
};
use std::f64::consts::FRAC_1_SQRT_2;

flat_values! {
    /// roughdiffuse's numeric parameter.
    pub struct RoughDiffuseParameters {
        alpha,
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughDiffuse {
    alpha: f32,
    oren_nayar: OrenNayar,
}

impl RoughDiffuse {
    /// Oren–Nayar's σ for the RMS slope α: `α/√2`.
    #[inline]
    pub fn sigma_of_alpha<T: Real>(alpha: T) -> T {
        alpha.scale(FRAC_1_SQRT_2)
    }

    pub fn new(alpha: f64, use_fast_approx: bool) -> Result<Self, ParamError> {
        Self::with_sampling(alpha, use_fast_approx, Sampling::Cosine)
    }

    /// With Oren–Nayar's sampler (`Sampling::Cltc`) or the cosine.
    pub fn with_sampling(alpha: f64, use_fast_approx: bool, sampling: Sampling) -> Result<Self, ParamError> {
        let alpha = Self::SPEC.params[0].check(alpha)?;
        let model = if use_fast_approx { OrenNayarForm::Qualitative } else { OrenNayarForm::Full };
        Ok(Self {
            alpha: alpha as f32,
            oren_nayar: OrenNayar::with_sampling(Self::sigma_of_alpha(alpha), model, sampling)?,
        })
    }

    pub fn alpha(&self) -> f32 {
        self.alpha
    }

    pub fn use_fast_approx(&self) -> bool {
        self.oren_nayar.model() == OrenNayarForm::Qualitative
    }

    /// The Oren–Nayar model it evaluates.
    pub fn oren_nayar(&self) -> &OrenNayar {
        &self.oren_nayar
    }
}


impl KernelBrdf for RoughDiffuse {
    fn f32_kernel(&self) -> impl Kernel<f32> + '_ {
        self.oren_nayar.kernel()
    }
}

impl Registered for RoughDiffuse {
    const SPEC: ModelSpec = ModelSpec {
        name: "roughdiffuse",
        label: "roughdiffuse",
        summary: "Mitsuba 0.6's rough diffuse: full Oren–Nayar with σ = α/√2, or the qualitative one with `use_fast_approx`",
        params: &[
            // σ = α/√2: a fit stays at α ≥ 1e-3 for Oren–Nayar's reason (σ = 0 is stationary).
            ParamSpec::number("alpha", 0.2, Range::AtLeast(0.0), "be a finite RMS slope >= 0", "RMS slope α (σ = α/√2)")
                .with_fit(1e-3, 2.0),
            ParamSpec::flag("use_fast_approx", false, "the qualitative model instead of the full one"),
            ParamSpec::sampling("`cosine`: as `diffuse`; `cltc`: Oren–Nayar's fitted sampler"),
        ],
        examples: &[&[("alpha", "0.6"), ("use_fast_approx", "true")]],
        in_study: false,
    };
    type Lane<'t, T: Real + 't> = OrenNayarKernel<T>;

    fn build(v: &Values) -> Result<Self, ParamError> {
        Self::with_sampling(v.number(param!("alpha")), v.flag(param!("use_fast_approx")), Sampling::parse(v.choice(param!("sampling"))))
    }

    fn values(&self) -> Vec<ParamValue> {
        parameter_values!(
            alpha: self.alpha,
            use_fast_approx: self.use_fast_approx(),
            sampling: self.oren_nayar.sampling().as_str(),
        )
    }

    type Parameters<T: Real> = RoughDiffuseParameters<T>;
    type Coefficients<T: Real> = OrenNayarCoefficients<T>;

    fn constant_coefficients<T: Real>(&self, p: RoughDiffuseParameters<T>, _: Gradients) -> OrenNayarCoefficients<T> {
        OrenNayarCoefficients::new(Self::sigma_of_alpha(p.alpha))
    }

    fn kernel_from<'t, T: Real + 't>(
        &self,
        c: OrenNayarCoefficients<T>,
        _: &[T::Table<'t>],
        _: Evaluation,
    ) -> Option<OrenNayarKernel<T>> {
        Some(OrenNayarKernel::from_coefficients(c, self.oren_nayar.model()).with_sampling(self.oren_nayar.sampling()))
    }
}
