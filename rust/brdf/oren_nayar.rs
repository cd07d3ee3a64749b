//! Oren–Nayar (SIGGRAPH 1994): Lambertian V-cavities with Gaussian slope-angle distribution of
//! standard deviation σ (radians). The seed paper's eq. 1 is the qualitative model, garbled
//! (it has a stray division by `p_i` and keeps the radiance factor `E0 cos θi`); the BRDF forms
//! below are research page §2a (qualitative) and §2b (full: C1–C3 plus the ρ² interreflection
//! term), identical to Mitsuba 0.6 `roughdiffuse` with `useFastApprox` true / false.

use super::approx::{acos_unit, at_least};
use super::frame::{azimuthal_dot, both_above, sin_theta};
use super::model::DiffuseBrdf;
use super::params::{ParamError, Params};
use glam::Vec3;
use std::f32::consts::{FRAC_1_PI, FRAC_2_PI};

/// Which of the 1994 forms to evaluate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrenNayarModel {
    /// `A + B max(0, cos Δφ) sin α tan β` (the form the seed paper uses).
    Qualitative,
    /// Direct term with C1, C2, C3 and the two-bounce interreflection term (quadratic in ρ).
    Full,
}

impl OrenNayarModel {
    pub fn as_str(self) -> &'static str {
        match self {
            OrenNayarModel::Qualitative => "qualitative",
            OrenNayarModel::Full => "full",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrenNayar {
    sigma: f32,
    model: OrenNayarModel,
    /// `A = C1 = 1 − 0.5 σ²/(σ²+0.33)`.
    a: f32,
    /// `B = 0.45 σ²/(σ²+0.09)` (also the C2 prefactor).
    b: f32,
    /// `0.125 σ²/(σ²+0.09)`: the C3 prefactor.
    c3: f32,
    /// `0.17 σ²/(σ²+0.13)`: the interreflection prefactor.
    l2: f32,
}

impl OrenNayar {
    pub const DEFAULT_SIGMA: f64 = 0.3;

    pub fn new(sigma: f64, model: OrenNayarModel) -> Result<Self, ParamError> {
        if !(sigma >= 0.0) || !sigma.is_finite() {
            return Err(ParamError::new("sigma", format!("must be a finite angle >= 0 in radians (got {sigma})")));
        }
        let s2 = sigma * sigma;
        Ok(Self {
            sigma: sigma as f32,
            model,
            a: (1.0 - 0.5 * s2 / (s2 + 0.33)) as f32,
            b: (0.45 * s2 / (s2 + 0.09)) as f32,
            c3: (0.125 * s2 / (s2 + 0.09)) as f32,
            l2: (0.17 * s2 / (s2 + 0.13)) as f32,
        })
    }

    pub fn from_params(p: &mut Params) -> Result<Self, ParamError> {
        let sigma = p.number("sigma", Self::DEFAULT_SIGMA)?;
        let model = match p.choice("model", &["qualitative", "full"], "qualitative")? {
            "full" => OrenNayarModel::Full,
            _ => OrenNayarModel::Qualitative,
        };
        Self::new(sigma, model)
    }

    pub fn sigma(&self) -> f32 {
        self.sigma
    }

    pub fn model(&self) -> OrenNayarModel {
        self.model
    }

    /// Full model, §2b. α = max(θi, θo), β = min(θi, θo); cos Δφ signed, 0 when undefined.
    #[inline]
    fn eval_full<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        let (sin_i, sin_o) = (sin_theta(wi), sin_theta(wo));
        let sin_prod = sin_i * sin_o;
        let cos_phi = if sin_prod > 1e-7 { (azimuthal_dot(wi, wo) / sin_prod).clamp(-1.0, 1.0) } else { 0.0 };
        // α belongs to the direction with the smaller cosine.
        let (cos_alpha, sin_alpha, cos_beta, sin_beta) =
            if wi.z < wo.z { (wi.z, sin_i, wo.z, sin_o) } else { (wo.z, sin_o, wi.z, sin_i) };
        // Both cosines are > 0 here (`eval` returns early otherwise): A&S 4.4.46, error
        // ≤ 1.3·10⁻⁷ rad, instead of two out-of-line libm calls.
        let alpha = acos_unit(cos_alpha);
        let beta = acos_unit(cos_beta);
        let tan_beta = sin_beta / cos_beta.max(1e-7);
        // tan((α+β)/2) by the half-angle identity: no trig, finite while μi + μo > 0.
        let tan_half_sum = (sin_alpha + sin_beta) / (cos_alpha + cos_beta).max(1e-7);
        let two_beta_pi = beta * FRAC_2_PI;
        let c2 = if cos_phi >= 0.0 { self.b * sin_alpha } else { self.b * (sin_alpha - two_beta_pi.powi(3)) };
        let four_ab = 4.0 * alpha * beta * FRAC_1_PI * FRAC_1_PI;
        let c3 = self.c3 * four_ab * four_ab;
        let direct = self.a + cos_phi * c2 * tan_beta + (1.0 - cos_phi.abs()) * c3 * tan_half_sum;
        let inter = self.l2 * (1.0 - cos_phi * two_beta_pi * two_beta_pi);
        // The 1994 fit goes negative in forward-grazing configurations at large σ (σ = 1,
        // θi = 89°, θo ≈ 90°, Δφ = 180°: C2 tan β outweighs C1 and, for ρ < 1, the ρ² term).
        // A BRDF cannot be negative: the total is clamped at 0, which leaves the published
        // model untouched wherever it is valid (Table 2's albedos are unchanged).
        reflectance.map(|rho| (FRAC_1_PI * rho * (direct + rho * inter)).max(0.0))
    }
}

impl DiffuseBrdf for OrenNayar {
    /// `inline(always)`: with the full model's body the function exceeds the inliner's
    /// threshold, and a call would cost the default (qualitative) model a third of its time.
    #[inline(always)]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        if !both_above(wi, wo) {
            return [0.0; N];
        }
        match self.model {
            OrenNayarModel::Qualitative => {
                // Trig-free form: max(0, cos Δφ) sin α tan β = max(0, s) / max(μi, μo). The
                // denominator is cos β; clamped as tan β is in the full model (both grazing).
                // B / cos β is formed first, so the division overlaps the dot product instead
                // of following it; single-instruction clamps (`approx::at_least`).
                let b_over_cos_beta = self.b / at_least(at_least(wi.z, wo.z), 1e-7);
                let g = at_least(azimuthal_dot(wi, wo), 0.0).mul_add(b_over_cos_beta, self.a);
                reflectance.map(|rho| rho * FRAC_1_PI * g)
            }
            OrenNayarModel::Full => self.eval_full(wi, wo, reflectance),
        }
    }
}
