//! Energy-preserving Oren–Nayar (Portsmouth, Kutz, Hill, JCGT 14(1) 2025):
//! Fujii's single-scattering form plus an analytic multiple-scattering lobe so that a white
//! surface reflects all light at every incidence. Roughness `r ∈ [0, 1]` is OpenPBR's
//! `base_diffuse_roughness`, not the Oren–Nayar σ. matte uses the **exact** FON albedo E_F
//! (closed form G(μ)), not the polynomial fit, so the white furnace is 1 to float precision.

use crate::approx::acos_unit;
use crate::cltc::ClippedLtc;
pub use crate::cltc::Sampling;
use crate::kernel::{Kernel, azimuthal_dot};
use crate::params::{ParamError, ParamValue};
use crate::real::{Real, V3};
use crate::registry::{
    Evaluation, Gradients, KernelBrdf, ModelSpec, ParamSpec, Registered, Values, flat_values, param, parameter_values,
};
use std::f64::consts::PI;

const C1: f64 = 0.5 - 2.0 / (3.0 * PI);
const C2: f64 = 2.0 / 3.0 - 28.0 / (15.0 * PI);

flat_values! {
    /// EON's numeric parameter.
    pub struct EonParameters {
        roughness,
    }
}

flat_values! {
    /// EON's roughness-derived constants in any [`Real`] (f64 on the CPU, then rounded to f32;
    /// traced, so that the roughness gradient flows through them). The differences `1 − A_F`
    /// and `1 − Ē_F` are formed as products (`c1 r A_F`, `(c1 − c2) r A_F`): no cancellation
    /// at small r in any precision.
    pub struct EonCoefficients {
        /// `A_F = 1/(1 + c1 r)`.
        a_f,
        /// `B_F = r A_F`.
        b_f,
        /// `Ē_F = A_F (1 + c2 r)`: cosine-weighted average of E_F.
        e_avg,
        /// `1 − Ē_F`.
        one_minus_e_avg,
        /// `1 − A_F`.
        one_minus_a_f,
        /// `B_F / π`.
        b_f_over_pi,
        /// `1 / max(1 − Ē_F, 10⁻⁷)`: the lobe's normalisation, a multiplication per eval.
        inv_one_minus_e_avg,
        /// `r`, for the sampler's fits.
        r,
        /// `r^{1/8}`: the uniform component's roughness factor ([`EonKernel::sampler`]).
        r_eighth,
    }
}

impl<T: Real> EonCoefficients<T> {
    pub fn new(r: T) -> Self {
        let one = T::c(1.0);
        let a_f = one / r.fma(T::c(C1), one);
        let one_minus_e_avg = (r * a_f).scale(C1 - C2);
        Self {
            a_f,
            b_f: r * a_f,
            e_avg: a_f * r.fma(T::c(C2), one),
            one_minus_e_avg,
            one_minus_a_f: (r * a_f).scale(C1),
            b_f_over_pi: (r * a_f).scale(1.0 / PI),
            inv_one_minus_e_avg: one / one_minus_e_avg.max(T::c(1e-7)),
            r,
            // Three square roots (traceable, no pow); the clamp keeps the derivative finite.
            r_eighth: T::select(r.gt(T::c(0.0)), r.max(T::c(1e-12)).sqrt().sqrt().sqrt(), T::c(0.0)),
        }
    }
}

/// EON's evaluation with its constants in any [`Real`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EonKernel<T> {
    pub c: EonCoefficients<T>,
    /// Sample the lobe ([`EonKernel::sampler`]) rather than the cosine (the `sampling`
    /// parameter). Not a coefficient: the model sets it ([`EonKernel::with_sampling`]).
    cltc: bool,
}

/// `G(μ) = S (acos μ − S μ) + (2/3)[(S/μ)(1 − S³) − S]`, `S = √(1−μ²)`, the azimuth-integrated
/// Fujii term. `(S/μ)(1 − S³)` is rewritten as `S μ (1+S+S²)/(1+S)` (using `1−S = μ²/(1+S)`):
/// no division by μ and no cancellation near grazing. `acos` is A&S 4.4.46 ([`acos_unit`],
/// error ≤ 1.3·10⁻⁷): libm's `acosf` is an out-of-line call and was half the eval's time.
#[inline(always)]
fn fon_g<T: Real>(mu: T) -> T {
    let one = T::c(1.0);
    let mu = mu.clamp_to(0.0, 1.0);
    let s = (one - mu * mu).safe_sqrt();
    // The reciprocal of 1 + S is formed while the numerator is: a shorter dependency chain.
    let t = s * mu * (one + s + s * s) * (one / (one + s));
    s * (acos_unit(mu) - s * mu) + (t - s).scale(2.0 / 3.0)
}

impl<T: Real> EonKernel<T> {
    pub fn new(r: T) -> Self {
        Self::from_coefficients(EonCoefficients::new(r))
    }

    /// The same kernel sampling the lobe (`Sampling::Cltc`) or the cosine.
    pub fn with_sampling(self, sampling: Sampling) -> Self {
        Self { cltc: sampling == Sampling::Cltc, ..self }
    }

    pub fn from_coefficients(c: EonCoefficients<T>) -> Self {
        Self { c, cltc: false }
    }

    /// The importance sampler at `μ = cos θi`: EON's CLTC fit (Portsmouth et al. 2025, §4 and
    /// the reference code's `ltc_coeffs`, `sample_EON`), entries rational in μ and polynomial
    /// in r. The uniform probability is the paper's cubic in μ times `r^{1/8}` where the paper
    /// has `r^{0.1}` (a defensive weight, not a fit to the lobe; `r^{1/8}` traces as three
    /// square roots): at most 0.163 at r = 1, 0 at r = 0, where the sampler is the cosine.
    #[inline(always)]
    pub fn sampler(&self, mu: T) -> ClippedLtc<T> {
        let one = T::c(1.0);
        let r = self.c.r;
        let poly2 = |c0: f64, c1: f64, c2: f64| T::c(c2).fma(mu, T::c(c1)).fma(mu, T::c(c0));
        let a = r.fma(poly2(0.303392, -0.518982, 0.111709) + r * T::c(0.335918).fma(mu, T::c(-0.276266)), one);
        let b_num = r * (T::c(1.15859).fma(mu, T::c(-1.16407)) + r * T::c(-0.150105).fma(mu, T::c(0.150815)));
        let b = b_num / (mu * mu).fma(mu, T::c(-1.43545));
        let c = r.fma(poly2(0.20013, -0.506373, 0.261777), one);
        let d = r * poly2(0.540852, -1.01625, 0.475392) / poly2(-1.0743, 0.0725628, 1.0);
        let cubic = T::c(-0.290822).fma(mu, T::c(0.538233)).fma(mu, T::c(-0.372058)).fma(mu, T::c(0.162925));
        ClippedLtc::new(a, b, c, d, self.c.r_eighth * cubic)
    }

    /// Exact single-scattering (FON) albedo `E_F(μ) = A_F + (B_F/π) G(μ)` for ρ = 1.
    #[inline(always)]
    pub fn fon_albedo(&self, mu: T) -> T {
        self.c.b_f_over_pi.fma(fon_g(mu), self.c.a_f)
    }

    /// `max(1 − E_F(μ), 10⁻⁷)`: the multiple-scattering lobe's factor per direction.
    #[inline(always)]
    fn fon_deficit(&self, mu: T) -> T {
        (self.c.one_minus_a_f - self.c.b_f_over_pi * fon_g(mu)).max(T::c(1e-7))
    }

    /// `ρ_ms = ρ² Ē / (1 − ρ(1 − Ē))`: the reference code's form (the OpenPBR text has a
    /// spurious extra 1/π; Portsmouth et al. 2025, listing 1).
    #[inline(always)]
    fn rho_ms(&self, rho: T) -> T {
        rho * rho * self.c.e_avg / (T::c(1.0) - rho * self.c.one_minus_e_avg).max(T::c(1e-7))
    }
}

impl<T: Real> Kernel<T> for EonKernel<T> {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        // Single scattering A_F (1 + r s/t), with s/t → s when s ≤ 0 (t = max(μi, μo)):
        // A_F + s⁺ (B_F/t) + s⁻ B_F. Written without a select (LLVM turns a select fed by a
        // division into a branch, which mispredicts half the time), and with B_F/t formed
        // while s is, not after it.
        let zero = T::c(0.0);
        let s = azimuthal_dot(wi, wo);
        let b_over_t = self.c.b_f / wi.z.max(wo.z).max(T::c(1e-7));
        let single = s.max(zero).fma(b_over_t, s.min(zero).fma(self.c.b_f, self.c.a_f));
        // ≥ 0 exactly for r ≤ 1 (s ≥ −1); the clamp removes f32 rounding at Δφ = π, grazing.
        let single = single.max(zero);
        let lobe = self.fon_deficit(wi.z) * self.fon_deficit(wo.z) * self.c.inv_one_minus_e_avg;
        rho.map(|r| r * single + self.rho_ms(r) * lobe)
    }

    #[inline(always)]
    fn fitted_sampler(&self) -> Option<impl Fn(T) -> ClippedLtc<T>> {
        self.cltc.then_some(move |mu| self.sampler(mu))
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eon {
    r: f32,
    sampling: Sampling,
    kernel: EonKernel<f32>,
}

impl Eon {
    pub fn new(r: f64) -> Result<Self, ParamError> {
        Self::with_sampling(r, Sampling::Cosine)
    }

    pub fn with_sampling(r: f64, sampling: Sampling) -> Result<Self, ParamError> {
        let r = Self::SPEC.params[0].check(r)?;
        let c = EonCoefficients::<f64>::new(r).map_values(|c| c as f32);
        let kernel = EonKernel::from_coefficients(c).with_sampling(sampling);
        Ok(Self { r: r as f32, sampling, kernel })
    }

    pub fn roughness(&self) -> f32 {
        self.r
    }

    pub fn kernel(&self) -> &EonKernel<f32> {
        &self.kernel
    }

    /// Exact single-scattering (FON) albedo `E_F(μ)` for ρ = 1.
    pub fn fon_albedo(&self, mu: f32) -> f32 {
        self.kernel.fon_albedo(mu)
    }
}


impl KernelBrdf for Eon {
    fn f32_kernel(&self) -> impl Kernel<f32> + '_ {
        &self.kernel
    }

    /// `E = ρ E_F(μi) + ρ_ms (1 − E_F(μi))` (Portsmouth et al. 2025, eq. 17).
    fn closed_form_albedo(&self, cos_theta_i: f64, reflectance: f32) -> Option<f64> {
        let e_f = self.fon_albedo(cos_theta_i as f32) as f64;
        let rho = reflectance as f64;
        let e_avg = self.kernel.c.e_avg as f64;
        let rho_ms = rho * rho * e_avg / (1.0 - rho * (1.0 - e_avg));
        Some(rho * e_f + rho_ms * (1.0 - e_f))
    }
}

impl Registered for Eon {
    const SPEC: ModelSpec = ModelSpec {
        name: "eon",
        label: "EON",
        summary: "energy-preserving Oren–Nayar (Portsmouth et al. 2025), exact albedo: the white furnace gives 1",
        params: &[
            ParamSpec::unit_interval("roughness", 0.3, "roughness r ∈ [0, 1] (OpenPBR `base_diffuse_roughness`)"),
            ParamSpec::sampling(
                "`cosine`: as `diffuse`; `cltc`: the paper's clipped linearly transformed cosine with a uniform share",
            ),
        ],
        examples: &[&[("roughness", "1.0")], &[("roughness", "1.0"), ("sampling", "cltc")]],
        in_study: true,
    };
    type Lane<'t, T: Real + 't> = EonKernel<T>;

    fn build(v: &Values) -> Result<Self, ParamError> {
        Self::with_sampling(v.number(param!("roughness")), Sampling::parse(v.choice(param!("sampling"))))
    }

    fn values(&self) -> Vec<ParamValue> {
        parameter_values!(roughness: self.r, sampling: self.sampling.as_str())
    }

    type Parameters<T: Real> = EonParameters<T>;
    type Coefficients<T: Real> = EonCoefficients<T>;

    fn constant_coefficients<T: Real>(&self, p: EonParameters<T>, _: Gradients) -> EonCoefficients<T> {
        EonCoefficients::new(p.roughness)
    }

    fn kernel_from<'t, T: Real + 't>(&self, c: EonCoefficients<T>, _: &[T::Table<'t>], _: Evaluation) -> Option<EonKernel<T>> {
        Some(EonKernel::from_coefficients(c).with_sampling(self.sampling))
    }
}
