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

use super::frame::{azimuthal_dot, both_above, sin_theta};
use super::model::DiffuseBrdf;
use super::params::{ParamError, Params};
use glam::Vec3;
use shadowing::{Shadowing, azimuth_correlation, azimuth_correlation_f32, mu_lambda, visibility_denominator};
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
    #[inline]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        if !both_above(wi, wo) {
            return [0.0; N];
        }
        let (mu_i, mu_o) = (wi.z.clamp(MIN_COS, 1.0), wo.z.clamp(MIN_COS, 1.0));
        let (si, so) = (sin_theta(wi), sin_theta(wo));
        let sin_prod = si * so;
        let cos_phi = if sin_prod > 1e-12 { (azimuthal_dot(wi, wo) / sin_prod).clamp(-1.0, 1.0) } else { 1.0 };
        let (x_i, x_o) = (table::axis_of_cos(mu_i), table::axis_of_cos(mu_o));
        let integral = self.table.lookup(x_i, x_o, cos_phi);
        let den = visibility_denominator(self.shadowing, mu_i, mu_o, self.table.mu_lambda(x_i), self.table.mu_lambda(x_o), || {
            azimuth_correlation_f32(cos_phi)
        });
        let g = FRAC_1_PI * integral / den;
        reflectance.map(|rho| rho * g)
    }
}
