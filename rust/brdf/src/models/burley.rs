//! Burley's diffuse (Burley 2012, "Physically-Based Shading at Disney", §5.3): Lambert with
//! Schlick-like Fresnel factors at both directions and a roughness-driven retro-reflection,
//! the diffuse lobe of Disney's BRDF and of Mitsuba's `principled` (flatness 0):
//!
//! `π f = ρ (f_d + f_r)`, `f_d = (1 − F_i/2)(1 − F_o/2)`,
//! `f_r = R_R (F_i + F_o + F_i F_o (R_R − 1))`, `F = (1 − μ)⁵`, `R_R = 2 r cos²θ_d`,
//!
//! with θ_d the angle between either direction and the half vector, so that
//! `cos²θ_d = (1 + wi·wo)/2` (no normalisation, no square root). Reciprocal; not energy
//! conserving (the retro-reflection adds light at grazing for large r), as published.

use crate::cltc::{ClippedLtc, Sampling};
use crate::kernel::Kernel;
use crate::params::{ParamError, ParamValue};
use crate::real::{Real, V3};
use crate::registry::{
    Evaluation, Gradients, KernelBrdf, ModelSpec, ParamSpec, Registered, Values, flat_values, param, parameter_values,
};
use crate::sampler_fits::BURLEY;

/// Burley's diffuse with its roughness in any [`Real`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BurleyKernel<T> {
    pub roughness: T,
    /// Sample the fitted lobe ([`BurleyKernel::sampler`]) rather than the cosine (the
    /// `sampling` parameter). Not a coefficient: the model sets it.
    pub cltc: bool,
}

impl<T: Real> BurleyKernel<T> {
    /// The importance sampler at `μ = cos θi`: the CLTC fitted to the model
    /// (`rust/brdf/src/sampler_fits.rs`, `validation/generators/fit_samplers.py`), polynomial in μ and the
    /// roughness r (clamped into [0, 1]); the cosine at r = 0.
    #[inline(always)]
    pub fn sampler(&self, mu: T) -> ClippedLtc<T> {
        BURLEY.sampler(mu, self.roughness)
    }
}

/// `(1 − μ)⁵`, with μ clamped into [0, 1].
#[inline(always)]
fn schlick_weight<T: Real>(mu: T) -> T {
    let m = T::c(1.0) - mu.clamp_to(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

impl<T: Real> Kernel<T> for BurleyKernel<T> {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        let one = T::c(1.0);
        let (f_i, f_o) = (schlick_weight(wi.z), schlick_weight(wo.z));
        let f_diffuse = (one - f_i.scale(0.5)) * (one - f_o.scale(0.5));
        // R_R = 2 r cos²θd = r (1 + wi·wo).
        let cos = wi.x * wo.x + wi.y * wo.y + wi.z * wo.z;
        let r_r = self.roughness * (one + cos);
        let f_retro = r_r * (f_i + f_o + f_i * f_o * (r_r - one));
        let g = f_diffuse + f_retro;
        rho.map(|r| r * g)
    }

    #[inline(always)]
    fn fitted_sampler(&self) -> Option<impl Fn(T) -> ClippedLtc<T>> {
        self.cltc.then_some(move |mu| self.sampler(mu))
    }
}

flat_values! {
    /// Burley's numeric parameter, which is also its kernel's constant.
    pub struct BurleyParameters {
        roughness,
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Burley {
    kernel: BurleyKernel<f32>,
    sampling: Sampling,
}

impl Burley {
    pub fn new(roughness: f64) -> Result<Self, ParamError> {
        Self::with_sampling(roughness, Sampling::Cosine)
    }

    pub fn with_sampling(roughness: f64, sampling: Sampling) -> Result<Self, ParamError> {
        let r = Self::SPEC.params[0].check(roughness)?;
        Ok(Self { kernel: BurleyKernel { roughness: r as f32, cltc: sampling == Sampling::Cltc }, sampling })
    }

    pub fn roughness(&self) -> f32 {
        self.kernel.roughness
    }
}


impl KernelBrdf for Burley {
    fn f32_kernel(&self) -> impl Kernel<f32> + '_ {
        &self.kernel
    }
}

impl Registered for Burley {
    const SPEC: ModelSpec = ModelSpec {
        name: "burley",
        label: "Burley",
        summary: "Burley 2012 (Disney): Lambert with Fresnel-like grazing factors and a roughness-driven retro-reflection; `principled`'s diffuse lobe",
        params: &[
            ParamSpec::unit_interval("roughness", 0.5, "roughness r ∈ [0, 1] (Disney's, as `principled`'s)"),
            ParamSpec::sampling(
                "`cosine`: as `diffuse`; `cltc`: a clipped linearly transformed cosine with a uniform share fitted to the model",
            ),
        ],
        examples: &[&[("roughness", "1.0")], &[("roughness", "1.0"), ("sampling", "cltc")]],
        in_study: true,
    };
    type Lane<'t, T: Real + 't> = BurleyKernel<T>;

    fn build(v: &Values) -> Result<Self, ParamError> {
        Self::with_sampling(v.number(param!("roughness")), Sampling::parse(v.choice(param!("sampling"))))
    }

    fn values(&self) -> Vec<ParamValue> {
        parameter_values!(roughness: self.kernel.roughness, sampling: self.sampling.as_str())
    }

    type Parameters<T: Real> = BurleyParameters<T>;
    type Coefficients<T: Real> = BurleyParameters<T>;

    fn constant_coefficients<T: Real>(&self, p: BurleyParameters<T>, _: Gradients) -> BurleyParameters<T> {
        p
    }

    fn kernel_from<'t, T: Real + 't>(
        &self,
        c: BurleyParameters<T>,
        _: &[T::Table<'t>],
        _: Evaluation,
    ) -> Option<BurleyKernel<T>> {
        Some(BurleyKernel { roughness: c.roughness, cltc: self.kernel.cltc })
    }
}
