//! Energy-preserving Oren–Nayar (Portsmouth, Kutz, Hill, JCGT 14(1) 2025; research page §2c):
//! Fujii's single-scattering form plus an analytic multiple-scattering lobe so that a white
//! surface reflects all light at every incidence. Roughness `r ∈ [0, 1]` is OpenPBR's
//! `base_diffuse_roughness`, not the Oren–Nayar σ. matte uses the **exact** FON albedo E_F
//! (closed form G(μ)), not the polynomial fit, so the white furnace is 1 to float precision.

use super::approx::{acos_unit, at_least, at_most};
use super::frame::{azimuthal_dot, both_above};
use super::model::{Albedo, AlbedoMethod, DiffuseBrdf};
use super::params::{ParamError, Params};
use glam::Vec3;
use std::f64::consts::PI;

const C1: f64 = 0.5 - 2.0 / (3.0 * PI);
const C2: f64 = 2.0 / 3.0 - 28.0 / (15.0 * PI);

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eon {
    r: f32,
    /// `A_F = 1/(1 + c1 r)`.
    a_f: f32,
    /// `B_F = r A_F`.
    b_f: f32,
    /// `Ē_F = A_F (1 + c2 r)`: cosine-weighted average of E_F.
    e_avg: f32,
    /// `1 − A_F` (f64 before rounding: no cancellation at small r).
    one_minus_a_f: f32,
    /// `B_F / π`.
    b_f_over_pi: f32,
    /// `1 / max(1 − Ē_F, 10⁻⁷)`: the lobe's normalisation, a multiplication per eval.
    inv_one_minus_e_avg: f32,
}

/// `G(μ) = S (acos μ − S μ) + (2/3)[(S/μ)(1 − S³) − S]`, `S = √(1−μ²)`, the azimuth-integrated
/// Fujii term. `(S/μ)(1 − S³)` is rewritten as `S μ (1+S+S²)/(1+S)` (using `1−S = μ²/(1+S)`):
/// no division by μ and no cancellation near grazing. `acos` is A&S 4.4.46 ([`acos_unit`],
/// error ≤ 1.3·10⁻⁷): libm's `acosf` is an out-of-line call and was half the eval's time.
#[inline]
fn fon_g(mu: f32) -> f32 {
    let mu = at_most(at_least(mu, 0.0), 1.0);
    let s = (1.0 - mu * mu).sqrt();
    // The reciprocal of 1 + S is formed while the numerator is: a shorter dependency chain.
    let t = s * mu * (1.0 + s + s * s) * (1.0 + s).recip();
    s * (acos_unit(mu) - s * mu) + (2.0 / 3.0) * (t - s)
}

impl Eon {
    pub const DEFAULT_ROUGHNESS: f64 = 0.3;

    pub fn new(r: f64) -> Result<Self, ParamError> {
        if !(0.0..=1.0).contains(&r) {
            return Err(ParamError::new("roughness", format!("must lie in [0, 1] (got {r})")));
        }
        let a_f = 1.0 / (1.0 + C1 * r);
        let b_f = r * a_f;
        let e_avg = a_f * (1.0 + C2 * r);
        Ok(Self {
            r: r as f32,
            a_f: a_f as f32,
            b_f: b_f as f32,
            e_avg: e_avg as f32,
            one_minus_a_f: (1.0 - a_f) as f32,
            b_f_over_pi: (b_f / PI) as f32,
            inv_one_minus_e_avg: (1.0 / (1.0 - e_avg).max(1e-7)) as f32,
        })
    }

    pub fn from_params(p: &mut Params) -> Result<Self, ParamError> {
        Self::new(p.number("roughness", Self::DEFAULT_ROUGHNESS)?)
    }

    pub fn roughness(&self) -> f32 {
        self.r
    }

    /// Exact single-scattering (FON) albedo `E_F(μ) = A_F + (B_F/π) G(μ)` for ρ = 1.
    #[inline]
    pub fn fon_albedo(&self, mu: f32) -> f32 {
        self.a_f + self.b_f_over_pi * fon_g(mu)
    }

    /// `max(1 − E_F(μ), 10⁻⁷)`: the multiple-scattering lobe's factor per direction.
    #[inline]
    fn fon_deficit(&self, mu: f32) -> f32 {
        at_least(self.one_minus_a_f - self.b_f_over_pi * fon_g(mu), 1e-7)
    }

    /// `ρ_ms = ρ² Ē / (1 − ρ(1 − Ē))`: the reference code's form (the OpenPBR text has a
    /// spurious extra 1/π, research page §2c).
    #[inline]
    fn rho_ms(&self, rho: f32) -> f32 {
        rho * rho * self.e_avg / (1.0 - rho * (1.0 - self.e_avg)).max(1e-7)
    }
}

impl DiffuseBrdf for Eon {
    #[inline]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        if !both_above(wi, wo) {
            return [0.0; N];
        }
        // Single scattering A_F (1 + r s/t), with s/t → s when s ≤ 0 (t = max(μi, μo)):
        // A_F + s⁺ (B_F/t) + s⁻ B_F. Written without a select (LLVM turns a select fed by a
        // division into a branch, which mispredicts half the time), and with B_F/t formed
        // while s is, not after it.
        let s = azimuthal_dot(wi, wo);
        let b_over_t = self.b_f / at_least(at_least(wi.z, wo.z), 1e-7);
        let single = at_least(s, 0.0).mul_add(b_over_t, at_most(s, 0.0).mul_add(self.b_f, self.a_f));
        // ≥ 0 exactly for r ≤ 1 (s ≥ −1); the clamp removes f32 rounding at Δφ = π, grazing.
        let single = at_least(single, 0.0);
        let lobe = self.fon_deficit(wi.z) * self.fon_deficit(wo.z) * self.inv_one_minus_e_avg;
        reflectance.map(|rho| std::f32::consts::FRAC_1_PI * (rho * single + self.rho_ms(rho) * lobe))
    }

    /// `E = ρ E_F(μi) + ρ_ms (1 − E_F(μi))` (research page §2c).
    fn albedo(&self, cos_theta_i: f64, reflectance: f32) -> Albedo {
        if cos_theta_i <= 0.0 {
            return Albedo { value: 0.0, method: AlbedoMethod::ClosedForm };
        }
        let e_f = self.fon_albedo(cos_theta_i as f32) as f64;
        let rho = reflectance as f64;
        let e_avg = self.e_avg as f64;
        let rho_ms = rho * rho * e_avg / (1.0 - rho * (1.0 - e_avg));
        Albedo { value: rho * e_f + rho_ms * (1.0 - e_f), method: AlbedoMethod::ClosedForm }
    }
}
