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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brdf::frame::spherical_direction_f64;
    use glam::DVec3;
    use table::{C_NODES, LAMBDA_NODES, U_NODES};

    /// The fast path written the plain way in f64 on the same table: two-square-root axis,
    /// `acos` for Δφ, nested linear interpolations, [`visibility_denominator`].
    fn fast_path_f64(g: &Ginneken, wi: DVec3, wo: DVec3) -> f64 {
        let (mu_i, mu_o) = (wi.z.clamp(MIN_COS as f64, 1.0), wo.z.clamp(MIN_COS as f64, 1.0));
        let (si, so) = (wi.truncate().length(), wo.truncate().length());
        let cos_phi = if si * so > 1e-12 { ((wi.x * wo.x + wi.y * wo.y) / (si * so)).clamp(-1.0, 1.0) } else { 1.0 };
        let axis = |mu: f64| {
            let (a, b) = ((1.0 - mu).sqrt(), mu.sqrt());
            a / (a + b)
        };
        let cell = |x: f64, n: usize| {
            let s = x.clamp(0.0, 1.0) * (n - 1) as f64;
            let i = (s.floor() as usize).min(n - 2);
            (i, s - i as f64)
        };
        let lerp = |a: f64, b: f64, t: f64| a + t * (b - a);
        let t = &g.table;
        let (xi, xo) = (axis(mu_i), axis(mu_o));
        let ((i, fi), (o, fo), (c, fc)) = (cell(xi, U_NODES), cell(xo, U_NODES), cell(0.5 * (cos_phi + 1.0), C_NODES));
        let at = |i: usize, o: usize| lerp(t.node(i, o, c) as f64, t.node(i, o, c + 1) as f64, fc);
        let integral = lerp(lerp(at(i, o), at(i, o + 1), fo), lerp(at(i + 1, o), at(i + 1, o + 1), fo), fi);
        let ml = |x: f64| {
            let (k, f) = cell(x, LAMBDA_NODES);
            lerp(t.lambda_node(k) as f64, t.lambda_node(k + 1) as f64, f)
        };
        let den = visibility_denominator(g.shadowing, mu_i, mu_o, ml(xi), ml(xo), || azimuth_correlation(cos_phi));
        integral / (std::f64::consts::PI * den)
    }

    /// The f32 eval (one-root axis, atan2 angle, weighted-sum interpolation, single division)
    /// is the same function as the plain f64 evaluation of the table to 6e-5 relative, for
    /// θ up to 89.5°. The largest differences are at grazing, where the table's value changes
    /// by a large factor from one node to the next, so the f32 rounding of the axis coordinate
    /// (~2e-7, i.e. 2e-5 of a cell) moves the value by a few 1e-5 (measured 3.3e-5 at m = 1,
    /// θo = 88.9°); for θ ≤ 80° about 1e-6. The table's own error against the integral is the
    /// separate 0.5 % bound of `tests/ginneken_fast_path.rs`.
    #[test]
    fn fast_path_is_its_f64_evaluation_to_rounding() {
        // R3 quasi-random sequence (Roberts 2018), as in `accuracy`.
        let g3 = 1.220_744_084_605_759_5_f64;
        let alpha = [1.0 / g3, 1.0 / (g3 * g3), 1.0 / (g3 * g3 * g3)];
        for m in [0.05, 0.3, 1.0] {
            for shadowing in [Shadowing::VanGinneken, Shadowing::HeightCorrelated] {
                let model = Ginneken::new(m, shadowing).unwrap();
                let mut worst = (0.0f64, DVec3::ZERO, DVec3::ZERO);
                for k in 0..20_000 {
                    let x: Vec<f64> = alpha.iter().map(|a| (0.5 + a * (k as f64 + 1.0)).fract()).collect();
                    let (ti, to, ph) = (x[0] * 89.5f64.to_radians(), x[1] * 89.5f64.to_radians(), x[2] * std::f64::consts::TAU);
                    let wi = spherical_direction_f64(ti, 0.3).as_vec3();
                    let wo = spherical_direction_f64(to, 0.3 + ph).as_vec3();
                    let got = model.eval(wi, wo, [1.0])[0] as f64;
                    let want = fast_path_f64(&model, wi.as_dvec3(), wo.as_dvec3());
                    let err = (got - want).abs() / want;
                    if err > worst.0 {
                        worst = (err, wi.as_dvec3(), wo.as_dvec3());
                    }
                }
                assert!(worst.0 <= 6e-5, "m = {m} {shadowing:?}: relative error {:e} at {:?}", worst.0, (worst.1, worst.2));
            }
        }
    }
}
