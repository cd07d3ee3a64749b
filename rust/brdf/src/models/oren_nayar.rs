//! Oren–Nayar (SIGGRAPH 1994): Lambertian V-cavities with Gaussian slope-angle distribution of
//! standard deviation σ (radians). The seed paper's eq. 1 is the qualitative model, garbled
//! (it has a stray division by `p_i` and keeps the radiance factor `E0 cos θi`); the BRDF forms
//! below are Oren & Nayar's qualitative model (1994, eq. 30) and their full model (C1–C3 plus the
//! ρ² interreflection term, eqs. 27–29 and 37), identical to Mitsuba 0.6 `roughdiffuse` with `useFastApprox` true / false.

use crate::approx::acos_unit;
use crate::cltc::{ClippedLtc, Sampling};
use crate::kernel::{Kernel, azimuthal_dot};
use crate::params::{ParamError, ParamValue};
use crate::real::{Real, V3};
use crate::registry::{
    Evaluation, Gradients, KernelBrdf, ModelSpec, ParamSpec, Range, Registered, Values, flat_values, param,
    parameter_values,
};
use crate::sampler_fits::{OREN_NAYAR_FULL, OREN_NAYAR_QUALITATIVE};
use std::f64::consts::{FRAC_1_PI, FRAC_2_PI};

/// Which of the 1994 forms to evaluate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrenNayarForm {
    /// `A + B max(0, cos Δφ) sin α tan β` (the form the seed paper uses).
    Qualitative,
    /// Direct term with C1, C2, C3 and the two-bounce interreflection term (quadratic in ρ).
    Full,
}

impl OrenNayarForm {
    pub fn as_str(self) -> &'static str {
        match self {
            OrenNayarForm::Qualitative => "qualitative",
            OrenNayarForm::Full => "full",
        }
    }
}

flat_values! {
    /// Oren–Nayar's numeric parameter.
    pub struct OrenNayarParameters {
        sigma,
    }
}

flat_values! {
    /// Oren–Nayar's parameter-derived constants in any [`Real`] (f64 on the CPU, then rounded
    /// to f32; traced, so that σ's gradient flows through them).
    pub struct OrenNayarCoefficients {
        /// `A = C1 = 1 − 0.5 σ²/(σ²+0.33)`.
        a,
        /// `B = 0.45 σ²/(σ²+0.09)` (also the C2 prefactor).
        b,
        /// `0.125 σ²/(σ²+0.09)`: the C3 prefactor.
        c3,
        /// `0.17 σ²/(σ²+0.13)`: the interreflection prefactor.
        l2,
    }
}

impl<T: Real> OrenNayarCoefficients<T> {
    pub fn new(sigma: T) -> Self {
        let s2 = sigma * sigma;
        let ratio = |k: f64, d: f64| s2.scale(k) / (s2 + T::c(d));
        Self { a: T::c(1.0) - ratio(0.5, 0.33), b: ratio(0.45, 0.09), c3: ratio(0.125, 0.09), l2: ratio(0.17, 0.13) }
    }
}

/// Oren–Nayar's evaluation with its constants in any [`Real`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrenNayarKernel<T> {
    pub c: OrenNayarCoefficients<T>,
    pub model: OrenNayarForm,
    /// Sample the fitted lobe ([`OrenNayarKernel::sampler`]) rather than the cosine (the
    /// `sampling` parameter). Not a coefficient: the model sets it.
    pub cltc: bool,
}

impl<T: Real> OrenNayarKernel<T> {
    pub fn new(sigma: T, model: OrenNayarForm) -> Self {
        Self::from_coefficients(OrenNayarCoefficients::new(sigma), model)
    }

    /// The same kernel sampling the fitted lobe (`Sampling::Cltc`) or the cosine.
    pub fn with_sampling(self, sampling: Sampling) -> Self {
        Self { cltc: sampling == Sampling::Cltc, ..self }
    }

    pub fn from_coefficients(c: OrenNayarCoefficients<T>, model: OrenNayarForm) -> Self {
        Self { c, model, cltc: false }
    }

    /// The importance sampler at `μ = cos θi`: the CLTC fitted to the model
    /// (`rust/brdf/src/sampler_fits.rs`, `validation/generators/fit_samplers.py`), polynomial in μ and in
    /// `t = B/0.45 = σ²/(σ² + 0.09)` ∈ [0, 1), which maps every σ ≥ 0 onto a bounded interval
    /// and is the kernel's own coefficient (traced, no new constant). At σ = 0 it is the
    /// cosine; at normal incidence too (the lobe is then constant).
    #[inline(always)]
    pub fn sampler(&self, mu: T) -> ClippedLtc<T> {
        let t = self.c.b.scale(1.0 / 0.45);
        match self.model {
            OrenNayarForm::Qualitative => OREN_NAYAR_QUALITATIVE.sampler(mu, t),
            OrenNayarForm::Full => OREN_NAYAR_FULL.sampler(mu, t),
        }
    }

    /// Full model. α = max(θi, θo), β = min(θi, θo); cos Δφ signed, 0 when undefined.
    #[inline(always)]
    fn reduced_full<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        let tiny = T::c(1e-7);
        let sin_theta = |w: V3<T>| (w.x * w.x + w.y * w.y).sqrt();
        let (sin_i, sin_o) = (sin_theta(wi), sin_theta(wo));
        let sin_prod = sin_i * sin_o;
        let cos_phi =
            T::select(sin_prod.gt(tiny), (azimuthal_dot(wi, wo) / sin_prod.max(tiny)).clamp_to(-1.0, 1.0), T::c(0.0));
        // α belongs to the direction with the smaller cosine.
        let i_is_alpha = wi.z.lt(wo.z);
        let cos_alpha = T::select(i_is_alpha, wi.z, wo.z);
        let sin_alpha = T::select(i_is_alpha, sin_i, sin_o);
        let cos_beta = T::select(i_is_alpha, wo.z, wi.z);
        let sin_beta = T::select(i_is_alpha, sin_o, sin_i);
        // A&S 4.4.46, error ≤ 1.3·10⁻⁷ rad, instead of two out-of-line libm calls.
        let alpha = acos_unit(cos_alpha);
        let beta = acos_unit(cos_beta);
        let tan_beta = sin_beta / cos_beta.max(tiny);
        // tan((α+β)/2) by the half-angle identity: no trig, finite while μi + μo > 0.
        let tan_half_sum = (sin_alpha + sin_beta) / (cos_alpha + cos_beta).max(tiny);
        let two_beta_pi = beta.scale(FRAC_2_PI);
        let c2 = T::select(
            cos_phi.ge(T::c(0.0)),
            self.c.b * sin_alpha,
            self.c.b * (sin_alpha - two_beta_pi * two_beta_pi * two_beta_pi),
        );
        let four_ab = (alpha * beta).scale(4.0 * FRAC_1_PI * FRAC_1_PI);
        let c3 = self.c.c3 * four_ab * four_ab;
        let direct = self.c.a + cos_phi * c2 * tan_beta + (T::c(1.0) - cos_phi.abs()) * c3 * tan_half_sum;
        let inter = self.c.l2 * (T::c(1.0) - cos_phi * two_beta_pi * two_beta_pi);
        // The 1994 fit goes negative in forward-grazing configurations at large σ (σ = 1,
        // θi = 89°, θo ≈ 90°, Δφ = 180°: C2 tan β outweighs C1 and, for ρ < 1, the ρ² term).
        // A BRDF cannot be negative: the total is clamped at 0, which leaves the published
        // model untouched wherever it is valid (the albedos of `docs/models.md` Table 2 are unchanged; `docs/models.md#clamps`).
        rho.map(|r| (r * r.fma(inter, direct)).max(T::c(0.0)))
    }
}

impl<T: Real> Kernel<T> for OrenNayarKernel<T> {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        match self.model {
            OrenNayarForm::Qualitative => {
                // Trig-free form: max(0, cos Δφ) sin α tan β = max(0, s) / max(μi, μo). The
                // denominator is cos β; clamped as tan β is in the full model (both grazing).
                // B / cos β is formed first, so the division overlaps the dot product instead
                // of following it.
                let b_over_cos_beta = self.c.b / wi.z.max(wo.z).max(T::c(1e-7));
                let g = azimuthal_dot(wi, wo).max(T::c(0.0)).fma(b_over_cos_beta, self.c.a);
                rho.map(|r| r * g)
            }
            OrenNayarForm::Full => self.reduced_full(wi, wo, rho),
        }
    }

    #[inline(always)]
    fn fitted_sampler(&self) -> Option<impl Fn(T) -> ClippedLtc<T>> {
        self.cltc.then_some(move |mu| self.sampler(mu))
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrenNayar {
    sigma: f32,
    sampling: Sampling,
    kernel: OrenNayarKernel<f32>,
}

impl OrenNayar {
    pub fn new(sigma: f64, model: OrenNayarForm) -> Result<Self, ParamError> {
        Self::with_sampling(sigma, model, Sampling::Cosine)
    }

    pub fn with_sampling(sigma: f64, model: OrenNayarForm, sampling: Sampling) -> Result<Self, ParamError> {
        let sigma = Self::SPEC.params[0].check(sigma)?;
        let c = OrenNayarCoefficients::<f64>::new(sigma).map_values(|c| c as f32);
        Ok(Self { sigma: sigma as f32, sampling, kernel: OrenNayarKernel::from_coefficients(c, model).with_sampling(sampling) })
    }

    pub fn sampling(&self) -> Sampling {
        self.sampling
    }

    pub fn sigma(&self) -> f32 {
        self.sigma
    }

    pub fn model(&self) -> OrenNayarForm {
        self.kernel.model
    }

    pub fn kernel(&self) -> &OrenNayarKernel<f32> {
        &self.kernel
    }
}


impl KernelBrdf for OrenNayar {
    fn f32_kernel(&self) -> impl Kernel<f32> + '_ {
        &self.kernel
    }
}

impl Registered for OrenNayar {
    const SPEC: ModelSpec = ModelSpec {
        name: "oren_nayar",
        label: "Oren–Nayar",
        summary: "Oren–Nayar 1994: the qualitative A/B model, or the full C1–C3 model with the ρ² interreflection term",
        params: &[
            ParamSpec::number(
                "sigma",
                0.3,
                Range::AtLeast(0.0),
                "be a finite angle >= 0 in radians",
                "slope-angle standard deviation σ (radians)",
            )
            // The model depends on σ² only, so σ = 0 (Lambert) is a stationary point of any
            // loss: a fit starts and stays at σ ≥ 1e-3 (A(σ) = 1 − 1.5·10⁻⁶ there, Lambert for
            // any image), from where Adam's scale-free steps move.
            .with_fit(1e-3, 1.5),
            ParamSpec::choice(
                "model",
                &["qualitative", "full"],
                "qualitative",
                "`qualitative` (eq. 30) or `full` (C1–C3 and the ρ² interreflection term)",
            ),
            ParamSpec::sampling("`cosine`: as `diffuse`; `cltc`: a clipped linearly transformed cosine with a uniform share fitted to the model"),
        ],
        examples: &[&[("sigma", "0.8"), ("model", "full")], &[("sigma", "1.0"), ("sampling", "cltc")]],
        in_study: true,
    };
    type Lane<'t, T: Real + 't> = OrenNayarKernel<T>;

    fn build(v: &Values) -> Result<Self, ParamError> {
        let model = if v.choice(param!("model")) == "full" { OrenNayarForm::Full } else { OrenNayarForm::Qualitative };
        Self::with_sampling(v.number(param!("sigma")), model, Sampling::parse(v.choice(param!("sampling"))))
    }

    fn values(&self) -> Vec<ParamValue> {
        parameter_values!(sigma: self.sigma, model: self.model().as_str(), sampling: self.sampling.as_str())
    }

    type Parameters<T: Real> = OrenNayarParameters<T>;
    type Coefficients<T: Real> = OrenNayarCoefficients<T>;

    fn constant_coefficients<T: Real>(&self, p: OrenNayarParameters<T>, _: Gradients) -> OrenNayarCoefficients<T> {
        OrenNayarCoefficients::new(p.sigma)
    }

    fn kernel_from<'t, T: Real + 't>(
        &self,
        c: OrenNayarCoefficients<T>,
        _: &[T::Table<'t>],
        _: Evaluation,
    ) -> Option<OrenNayarKernel<T>> {
        Some(OrenNayarKernel::from_coefficients(c, self.model()).with_sampling(self.sampling))
    }
}
