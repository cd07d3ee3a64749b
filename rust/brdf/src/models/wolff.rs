//! Wolff (JOSA A 11(11), 1994): diffuse reflection from a smooth dielectric. Light is Fresnel
//! transmitted into the body at θi, scattered into an isotropic internal distribution and
//! transmitted out towards the viewer. As a BRDF (Wolff 1994, eq. 5 with the Fresnel terms of §2):
//!
//! `f = K · T(θi) · T(θo)`, `T(θ) = 1 − F(θ, n)`, n = int_ior / ext_ior,
//!
//! using the Stokes identity `1 − F(asin(sin θo / n), 1/n) = 1 − F(θo, n)` so that the exit
//! term needs no refraction (and the form is visibly reciprocal). The seed paper's radiance
//! form carries `cos θi`, which is the renderer's, not the kernel's.
//!
//! `K` is Wolff's lumped constant; matte offers three choices:
//! * `physical` (default): `ρ / (π n² (1 − ρ F_dr,int))`: isotropic internal radiance with all
//!   internally reflected light re-scattered (Mitsuba 0.6 `plastic` diffuse lobe, nonlinear);
//!   ρ is the internal single-bounce albedo; albedo `(1 − F(θi)) ρ(1−F_dr,int)/(1−ρF_dr,int)`.
//! * `normal`: `ρ / (π (1 − F(0)) (1 − F_dr,ext))`, scaled so that E(0°) = ρ (same albedo as
//!   Lambert at normal incidence; the fair side-by-side comparison).
//! * `raw`: `ρ / π`.

use crate::fresnel::{Transmittance, dielectric_reflectance, diffuse_fresnel_external};
use crate::fresnel_fit::diffuse_fresnel_external_fit;
use crate::kernel::Kernel;
use crate::params::{ParamError, ParamValue};
use crate::real::{Real, V3};
use crate::registry::{
    Evaluation, Gradients, KernelBrdf, ModelSpec, ParamSpec, Registered, Values, flat_values, param, parameter_values,
};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WolffNormalization {
    Physical,
    Normal,
    Raw,
}

impl WolffNormalization {
    pub fn as_str(self) -> &'static str {
        match self {
            WolffNormalization::Physical => "physical",
            WolffNormalization::Normal => "normal",
            WolffNormalization::Raw => "raw",
        }
    }
}

flat_values! {
    /// Wolff's numeric parameters.
    pub struct WolffParameters {
        int_ior,
        ext_ior,
    }
}

flat_values! {
    /// [`WolffKernel`]'s constants, as the traced plugin keeps them.
    pub struct WolffCoefficients {
        /// `n²` ([`Transmittance::n2`]).
        n2,
        /// `n² − 1` ([`Transmittance::n2_minus_1`]).
        n2_minus_1,
        /// [`WolffKernel::k_pi`].
        k_pi,
        /// [`WolffKernel::f_dr_int`].
        f_dr_int,
    }
}

/// Wolff's index-derived constants in any [`Real`] (f64 on the CPU, then rounded to f32;
/// traced, so that the indices' gradients flow through them), and its evaluation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WolffKernel<T> {
    /// The per-eval transmittance `1 − F(θ, n)`.
    pub transmittance: Transmittance<T>,
    /// The part of `π K` that does not depend on ρ: 1 (raw), `1/((1 − F(0)) (1 − F_dr,ext))`
    /// (normal), `1/n²` (physical).
    pub k_pi: T,
    /// `F_dr,int = F_dr(1/n)`: the hemispherical reflectance seen from inside (physical only).
    pub f_dr_int: T,
    pub normalization: WolffNormalization,
}

impl<T: Real> WolffKernel<T> {
    /// For relative index `n = int_ior / ext_ior ≥ 1`. `F_dr` is a 64-node quadrature: run
    /// once per parameter value, never per eval.
    pub fn new(n: T, normalization: WolffNormalization) -> Self {
        Self::with_average(n, normalization, |n| diffuse_fresnel_external(n))
    }

    /// The same constants with `F_dr` from its fit ([`diffuse_fresnel_external_fit`],
    /// |error| ≤ 2e-5): cheap enough per lane and call, for an index that varies per lane
    /// (a textured `int_ior`). `n` is taken as at least 1.
    pub fn per_lane(n: T, normalization: WolffNormalization) -> Self {
        Self::with_average(n.max(T::c(1.0)), normalization, |n| diffuse_fresnel_external_fit(n))
    }

    fn with_average(n: T, normalization: WolffNormalization, f_dr_ext: impl Fn(T) -> T) -> Self {
        let one = T::c(1.0);
        let k_pi = match normalization {
            WolffNormalization::Raw => one,
            // 1 − F(0) = 4n/(n+1)², without cancellation.
            WolffNormalization::Normal => {
                let n_plus_1 = n + one;
                n_plus_1 * n_plus_1 / (n.scale(4.0) * (one - f_dr_ext(n)))
            }
            WolffNormalization::Physical => one / (n * n),
        };
        // F_dr,int = F_dr(1/n) by the identity 1 − F_dr(1/n) = (1 − F_dr(n))/n²
        // (`fresnel::diffuse_fresnel_internal`).
        let f_dr_int = match normalization {
            WolffNormalization::Physical => one - (one - f_dr_ext(n)) / (n * n),
            _ => T::c(0.0),
        };
        Self { transmittance: Transmittance::new(n), k_pi, f_dr_int, normalization }
    }

    pub fn coefficients(&self) -> WolffCoefficients<T> {
        let Transmittance { n2, n2_minus_1 } = self.transmittance;
        WolffCoefficients { n2, n2_minus_1, k_pi: self.k_pi, f_dr_int: self.f_dr_int }
    }

    pub fn from_coefficients(c: WolffCoefficients<T>, normalization: WolffNormalization) -> Self {
        let transmittance = Transmittance { n2: c.n2, n2_minus_1: c.n2_minus_1 };
        Self { transmittance, k_pi: c.k_pi, f_dr_int: c.f_dr_int, normalization }
    }

    /// `π K` for one reflectance channel. ρ is clamped to [0, 1] for `physical`, whose
    /// geometric series diverges at ρ = 1/F_dr,int.
    #[inline(always)]
    pub fn k_pi(&self, rho: T) -> T {
        match self.normalization {
            WolffNormalization::Raw | WolffNormalization::Normal => rho * self.k_pi,
            WolffNormalization::Physical => {
                let rho = rho.clamp_to(0.0, 1.0);
                rho * self.k_pi / (T::c(1.0) - rho * self.f_dr_int)
            }
        }
    }
}

impl<T: Real> Kernel<T> for WolffKernel<T> {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        let t = self.transmittance.at(wi.z) * self.transmittance.at(wo.z);
        rho.map(|r| self.k_pi(r) * t)
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wolff {
    int_ior: f32,
    ext_ior: f32,
    /// Relative index `n = int_ior / ext_ior`.
    eta: f32,
    /// `F_dr,ext(n)`: cosine-weighted hemispherical Fresnel reflectance seen from outside.
    f_dr_ext: f32,
    kernel: WolffKernel<f32>,
}

impl Wolff {
    pub fn new(int_ior: f64, ext_ior: f64, normalization: WolffNormalization) -> Result<Self, ParamError> {
        let int_ior = Self::SPEC.params[0].check(int_ior)?;
        let ext_ior = Self::SPEC.params[1].check(ext_ior)?;
        let eta = int_ior / ext_ior;
        if eta < 1.0 {
            return Err(ParamError::new(
                "int_ior",
                format!(
                    "must be >= ext_ior: Wolff's model is a denser body under a smooth interface (got int_ior {int_ior} < ext_ior {ext_ior})"
                ),
            ));
        }
        let k = WolffKernel::<f64>::new(eta, normalization);
        let kernel = WolffKernel {
            transmittance: k.transmittance.rounded(),
            k_pi: k.k_pi as f32,
            f_dr_int: k.f_dr_int as f32,
            normalization,
        };
        Ok(Self {
            int_ior: int_ior as f32,
            ext_ior: ext_ior as f32,
            eta: eta as f32,
            f_dr_ext: diffuse_fresnel_external(eta) as f32,
            kernel,
        })
    }

    pub fn int_ior(&self) -> f32 {
        self.int_ior
    }
    pub fn ext_ior(&self) -> f32 {
        self.ext_ior
    }
    pub fn normalization(&self) -> WolffNormalization {
        self.kernel.normalization
    }
    pub fn kernel(&self) -> &WolffKernel<f32> {
        &self.kernel
    }
}


impl KernelBrdf for Wolff {
    fn f32_kernel(&self) -> impl Kernel<f32> + '_ {
        &self.kernel
    }

    /// `E(θi) = K T(θi) π (1 − F_dr,ext)`, since `∫ T(θo) cos θo dωo = π (1 − F_dr,ext)`.
    fn closed_form_albedo(&self, cos_theta_i: f64, reflectance: f32) -> Option<f64> {
        let t_i = 1.0 - dielectric_reflectance(cos_theta_i, self.eta as f64);
        Some(self.kernel.k_pi(reflectance) as f64 * t_i * (1.0 - self.f_dr_ext as f64))
    }
}

impl Registered for Wolff {
    const SPEC: ModelSpec = ModelSpec {
        name: "wolff",
        label: "Wolff",
        summary: "smooth dielectric, Fresnel in and out: `K·T(θi)·T(θo)`, T = 1 − Fresnel",
        params: &[
            ParamSpec::ior("int_ior", 1.4, "interior index of refraction (number or material name)"),
            ParamSpec::ior("ext_ior", 1.0, "exterior index of refraction"),
            ParamSpec::choice(
                "normalization",
                &["physical", "normal", "raw"],
                "physical",
                "`physical` (energy-conserving), `normal` (Wolff's normal-incidence scaling) or `raw`",
            ),
        ],
        examples: &[&[("int_ior", "bk7"), ("ext_ior", "1.1"), ("normalization", "normal")], &[("int_ior", "1.8"), ("normalization", "raw")]],
        in_study: true,
    };
    type Lane<'t, T: Real + 't> = WolffKernel<T>;

    fn build(v: &Values) -> Result<Self, ParamError> {
        let normalization = match v.choice(param!("normalization")) {
            "normal" => WolffNormalization::Normal,
            "raw" => WolffNormalization::Raw,
            _ => WolffNormalization::Physical,
        };
        Self::new(v.number(param!("int_ior")), v.number(param!("ext_ior")), normalization)
    }

    fn values(&self) -> Vec<ParamValue> {
        parameter_values!(int_ior: self.int_ior, ext_ior: self.ext_ior, normalization: self.normalization().as_str())
    }

    type Parameters<T: Real> = WolffParameters<T>;
    type Coefficients<T: Real> = WolffCoefficients<T>;

    /// The exact `F_dr` (a 64-node quadrature): once per parameter value.
    fn constant_coefficients<T: Real>(&self, p: WolffParameters<T>, _: Gradients) -> WolffCoefficients<T> {
        WolffKernel::new(p.int_ior / p.ext_ior, self.normalization()).coefficients()
    }

    /// `F_dr` from its fit ([`WolffKernel::per_lane`]); `ext_ior ≥ 1`, and `n ≥ 1` there.
    fn lane_coefficients<T: Real>(&self, p: WolffParameters<T>) -> WolffCoefficients<T> {
        WolffKernel::per_lane(p.int_ior / p.ext_ior.max(T::c(1.0)), self.normalization()).coefficients()
    }

    fn kernel_from<'t, T: Real + 't>(
        &self,
        c: WolffCoefficients<T>,
        _: &[T::Table<'t>],
        _: Evaluation,
    ) -> Option<WolffKernel<T>> {
        Some(WolffKernel::from_coefficients(c, self.normalization()))
    }

    /// The indices bound each other: `int_ior ≥ max(ext_ior, 1)`, `1 ≤ ext_ior ≤ int_ior`.
    fn placeholder(name: &str, mean: f64, number: &dyn Fn(&str) -> Option<f64>) -> f64 {
        let at_least = |lo: f64| if mean >= lo { mean } else { lo }; // NaN gives lo
        match name {
            "int_ior" => at_least(number("ext_ior").unwrap_or(1.0).max(1.0)),
            "ext_ior" => at_least(1.0).min(number("int_ior").unwrap_or(1.0).max(1.0)),
            _ => mean,
        }
    }
}
