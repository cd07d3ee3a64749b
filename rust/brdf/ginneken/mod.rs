//! van Ginneken, Stavridi & Koenderink (Appl. Opt. 37(1), 1998), diffuse part: Lambertian
//! facets on an isotropic Gaussian surface with per-axis rms slope `m`, shadowing and masking
//! by the seed paper's eq. 5 (research page §4):
//!
//! `f = (ρ/π) · P_ill+vis(wi, wo) · I(wi, wo) / (μi μo)`
//!
//! with the slope integral `I` ([`slope_integral`]) and `P_ill+vis` ([`shadowing`]). There is
//! no closed form for `I`: [`Ginneken::eval_reference`] integrates it (semi-analytically, f64)
//! and [`DiffuseBrdf::eval`] interpolates a per-roughness table of it ([`table`]). The seed's
//! text says the probability "multiplies the results from the Lambertian model using the
//! angles of eqs. 2–3", i.e. the facet-local cosines: that is the integrand of `I`.

pub mod accuracy;
pub mod shadowing;
pub mod slope_integral;
pub mod table;

use super::approx;
use super::frame::{azimuthal_dot, both_above};
use super::model::DiffuseBrdf;
use super::params::{ParamError, Params};
use glam::Vec3;
use shadowing::{Shadowing, azimuth_correlation, mu_lambda, visibility_denominator, visibility_fraction_f32};
use slope_integral::{REFERENCE_NODES, SlopeIntegrator};
use std::f32::consts::FRAC_1_PI;
use std::sync::Arc;
use table::SlopeTable;

/// Cosines are clamped to this before entering `1/(μi μo)`-type terms: f stays finite (the
/// model's back-scattering peak grows like 1/μ at grazing) without affecting any angle a
/// renderer can resolve.
const MIN_COS: f32 = 1e-7;

#[derive(Clone, Debug)]
pub struct Ginneken {
    m: f32,
    shadowing: Shadowing,
    table: Arc<SlopeTable>,
}

impl PartialEq for Ginneken {
    fn eq(&self, other: &Self) -> bool {
        self.m == other.m && self.shadowing == other.shadowing
    }
}

impl Ginneken {
    pub const DEFAULT_ROUGHNESS: f64 = 0.3;

    pub fn new(m: f64, shadowing: Shadowing) -> Result<Self, ParamError> {
        if !(m > 0.0) || !m.is_finite() {
            return Err(ParamError::new("roughness", format!("must be a finite rms slope > 0 (got {m})")));
        }
        if m > 4.0 {
            return Err(ParamError::new("roughness", format!("must be <= 4 (rms slope; 1 is already a 45° mean facet tilt) (got {m})")));
        }
        Ok(Self { m: m as f32, shadowing, table: SlopeTable::shared(m) })
    }

    pub fn from_params(p: &mut Params) -> Result<Self, ParamError> {
        let m = p.number("roughness", Self::DEFAULT_ROUGHNESS)?;
        let shadowing = match p.choice("shadowing", &["vginneken", "height_correlated"], "vginneken")? {
            "height_correlated" => Shadowing::HeightCorrelated,
            _ => Shadowing::VanGinneken,
        };
        Self::new(m, shadowing)
    }

    pub fn roughness(&self) -> f32 {
        self.m
    }

    pub fn shadowing(&self) -> Shadowing {
        self.shadowing
    }

    /// Reference value of `f` (f64, direct integration, ~1e-9 relative): for tests and for
    /// measuring the table's error. Slow (~10 µs).
    pub fn eval_reference(&self, wi: glam::DVec3, wo: glam::DVec3, reflectance: f64) -> f64 {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return 0.0;
        }
        thread_local! {
            static REFERENCE: SlopeIntegrator = SlopeIntegrator::new(REFERENCE_NODES);
        }
        let m = self.m as f64;
        let (si, so) = (wi.truncate().length(), wo.truncate().length());
        let cos_phi = if si * so > 1e-300 { ((wi.x * wo.x + wi.y * wo.y) / (si * so)).clamp(-1.0, 1.0) } else { 1.0 };
        let integral = REFERENCE.with(|r| r.integral(m, wi.z, wo.z, cos_phi.acos()));
        let den = visibility_denominator(self.shadowing, wi.z, wo.z, mu_lambda(wi.z, si, m), mu_lambda(wo.z, so, m), || {
            azimuth_correlation(cos_phi)
        });
        reflectance * std::f64::consts::FRAC_1_PI * integral / den
    }
}

impl DiffuseBrdf for Ginneken {
    #[inline(always)]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        if !both_above(wi, wo) {
            return [0.0; N];
        }
        let clamp_cos = |mu: f32| approx::at_most(approx::at_least(mu, MIN_COS), 1.0);
        let (mu_i, mu_o) = (clamp_cos(wi.z), clamp_cos(wo.z));
        // cos Δφ = s / (sin θi sin θo), s = wi·wo − μi μo; the product of the sines is one
        // square root of the product of the squared sines. Δφ itself (for the visibility) is
        // the angle of (s, c) with c = (wi × wo)·z, since s² + c² = sin²θi sin²θo: no acos
        // after this square root and division, which would make the chain longer.
        let s = azimuthal_dot(wi, wo);
        let sin2_prod = (wi.x * wi.x + wi.y * wi.y) * (wo.x * wo.x + wo.y * wo.y);
        let defined = sin2_prod > 1e-24;
        let cos_phi = if defined { approx::at_most(approx::at_least(s / sin2_prod.sqrt(), -1.0), 1.0) } else { 1.0 };
        let phi = if defined { approx::angle((wi.x * wo.y - wi.y * wo.x).abs(), s) } else { 0.0 };
        let (x_i, x_o) = (table::axis_of_cos(mu_i), table::axis_of_cos(mu_o));
        let (num, den) = visibility_fraction_f32(self.shadowing, mu_i, mu_o, self.table.mu_lambda(x_i), self.table.mu_lambda(x_o), phi);
        // num/den does not wait for the table lookup (usually a cache miss).
        let g = self.table.lookup(x_i, x_o, cos_phi) * (FRAC_1_PI * num / den);
        reflectance.map(|rho| rho * g)
    }
}
