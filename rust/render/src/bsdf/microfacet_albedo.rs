//! The rough-interface albedos `roughplastic` precomputes (Mitsuba 3.9.1
//! `include/mitsuba/render/microfacet.h`: `eval_transmittance`, `eval_reflectance`; used in
//! `src/bsdfs/roughplastic.cpp::parameters_changed`).
//!
//! Both integrate over the visible normals of `wi` with an N×N Gauss–Legendre rule on the
//! unit square of sample numbers, pushed through Mitsuba's own visible-normal warp (N = 32
//! for η > 1, 128 otherwise):
//!
//! ```text
//! T(wi) = Σ w·¼ · (1 − F(wi·m)) · G1(wt, m)   [wt = refract(wi, m), on the other side]
//! R(wi) = Σ w·¼ · F(wi·m) · G1(wr, m)         [wr = reflect(wi, m), above the surface]
//! ```
//!
//! The rule's error depends on the warp, so this file reproduces Mitsuba's warp
//! (`sample_visible_11`, incl. its three unguarded Newton steps for Beckmann) in f32 rather
//! than using the renderer's sampler ([`super::vndf`]), which draws the same density through
//! a different map.

use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, MicrofacetDistribution};
use super::vndf::erf_inv;
use glam::{Vec2, Vec3};
use matte_brdf::quadrature::GaussLegendre;
use matte_brdf::sampling::square_to_uniform_disk_concentric;

/// Mitsuba's `MI_ROUGH_TRANSMITTANCE_RES`: table size over cos θ ∈ [0, 1].
pub const TABLE_RES: usize = 64;

const INV_SQRT_PI: f32 = 0.564_189_6;

/// Mitsuba's `MicrofacetDistribution::sample` with visible normals (stretch, α = 1 slope
/// sample, rotate, unstretch), for `wi.z > 0`.
pub fn mitsuba_visible_normal(distr: &Microfacet, wi: Vec3, u: Vec2) -> Vec3 {
    let wi_p = Vec3::new(distr.alpha_u * wi.x, distr.alpha_v * wi.y, wi.z).normalize();
    let sin2 = wi_p.x.mul_add(wi_p.x, wi_p.y * wi_p.y);
    let (cos_phi, sin_phi) = if sin2.abs() <= 4.0 * f32::EPSILON / 2.0 {
        (1.0, 0.0)
    } else {
        let inv = sin2.sqrt().recip();
        ((wi_p.x * inv).clamp(-1.0, 1.0), (wi_p.y * inv).clamp(-1.0, 1.0))
    };
    let slope = sample_visible_11(distr.kind, wi_p.z, u);
    let sx = cos_phi.mul_add(slope.x, -(sin_phi * slope.y)) * distr.alpha_u;
    let sy = sin_phi.mul_add(slope.x, cos_phi * slope.y) * distr.alpha_v;
    Vec3::new(-sx, -sy, 1.0).normalize()
}

/// Mitsuba's `sample_visible_11`: slopes of the α = 1 visible-normal distribution.
fn sample_visible_11(kind: MicrofacetDistribution, cos_theta_i: f32, u: Vec2) -> Vec2 {
    match kind {
        MicrofacetDistribution::Beckmann => {
            let tan_theta_i = (1.0 - cos_theta_i * cos_theta_i).max(0.0).sqrt() / cos_theta_i;
            let cot_theta_i = tan_theta_i.recip();
            let maxval = libm::erff(cot_theta_i);
            let u = u.clamp(Vec2::splat(1e-6), Vec2::splat(1.0 - 1e-6));
            let mut x = maxval - (maxval + 1.0) * libm::erff((-u.x.ln()).sqrt());
            let target = u.x * (1.0 + maxval + INV_SQRT_PI * tan_theta_i * (-(cot_theta_i * cot_theta_i)).exp());
            for _ in 0..3 {
                let slope = erf_inv(x);
                let value = 1.0 + x + INV_SQRT_PI * tan_theta_i * (-(slope * slope)).exp() - target;
                let derivative = 1.0 - slope * tan_theta_i;
                x -= value / derivative;
            }
            Vec2::new(erf_inv(x), erf_inv(2.0f32.mul_add(u.y, -1.0)))
        }
        MicrofacetDistribution::Ggx => {
            let mut p = square_to_uniform_disk_concentric(u);
            let s = 0.5 * (1.0 + cos_theta_i);
            let a = (1.0 - p.x * p.x).max(0.0).sqrt();
            p.y = a + (p.y - a) * s;
            let (x, y) = (p.x, p.y);
            let z = (1.0 - p.length_squared()).max(0.0).sqrt();
            let sin_theta_i = (1.0 - cos_theta_i * cos_theta_i).max(0.0).sqrt();
            let norm = sin_theta_i.mul_add(y, cos_theta_i * z).recip();
            Vec2::new(cos_theta_i.mul_add(y, -(sin_theta_i * z)), x) * norm
        }
    }
}

/// The 2-D rule on [0, 1]²: (sample, weight·¼), weight from the [-1, 1]² rule as Mitsuba.
fn rule(eta: f32) -> Vec<(Vec2, f32)> {
    let n = if eta > 1.0 { 32 } else { 128 };
    let gl = GaussLegendre::new(n);
    let nodes: Vec<f32> = gl.nodes.iter().map(|&x| x as f32).collect();
    let weights: Vec<f32> = gl.weights.iter().map(|&w| w as f32).collect();
    let mut out = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let node = Vec2::new(nodes[i].mul_add(0.5, 0.5), nodes[j].mul_add(0.5, 0.5));
            out.push((node, weights[i] * weights[j] * 0.25));
        }
    }
    out
}

/// Mitsuba's table directions: μ_k = max(1e-6, k/63), wi = (√(1 − μ²), 0, μ).
fn table_directions() -> impl Iterator<Item = Vec3> {
    (0..TABLE_RES).map(|k| {
        let mu = (k as f32 / (TABLE_RES - 1) as f32).max(1e-6);
        Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu)
    })
}

/// `eval_transmittance` at the 64 table cosines: the fraction of light from outside that
/// crosses a rough interface of relative index `eta` (single scattering).
pub fn external_transmittance(kind: MicrofacetDistribution, alpha: f32, eta: f32) -> [f32; TABLE_RES] {
    let distr = Microfacet::new(kind, alpha, alpha);
    let rule = rule(eta);
    let mut out = [0.0; TABLE_RES];
    for (slot, wi) in out.iter_mut().zip(table_directions()) {
        let mut sum = 0.0f32;
        for &(u, w) in &rule {
            let m = mitsuba_visible_normal(&distr, wi, u);
            let f = fresnel_dielectric(wi.dot(m), eta);
            // Mitsuba's refract(wi, m, cos_t, eta_ti) = m·(wi·m·eta_ti + cos_t) − wi·eta_ti.
            let wo = m * wi.dot(m).mul_add(f.eta_ti, f.cos_t) - wi * f.eta_ti;
            let v = distr.smith_g1(wo, m) * (1.0 - f.r);
            if wo.z * wi.z < 0.0 {
                sum += v * w;
            }
        }
        *slot = sum;
    }
    out
}

/// Mitsuba's `m_internal_reflectance`: 2·mean_k(R(wi_k)·μ_k) over the table directions, R
/// from `eval_reflectance` with index 1/η (light inside the coating).
pub fn internal_reflectance(kind: MicrofacetDistribution, alpha: f32, eta: f32) -> f32 {
    let distr = Microfacet::new(kind, alpha, alpha);
    let inv_eta = 1.0 / eta;
    let rule = rule(inv_eta);
    let mut total = 0.0f32;
    for wi in table_directions() {
        let mut sum = 0.0f32;
        for &(u, w) in &rule {
            let m = mitsuba_visible_normal(&distr, wi, u);
            let wo = 2.0 * wi.dot(m) * m - wi;
            let f = fresnel_dielectric(wi.dot(m), inv_eta).r;
            if wo.z > 0.0 && wi.z > 0.0 {
                sum += distr.smith_g1(wo, m) * f * w;
            }
        }
        total += sum * wi.z;
    }
    total / TABLE_RES as f32 * 2.0
}

/// Mitsuba's `lerp_gather` on a table over [0, 1] (x clamped to the last interval's end).
#[inline]
pub fn lerp_table(table: &[f32; TABLE_RES], x: f32) -> f32 {
    let x = x * (TABLE_RES - 1) as f32;
    // `as usize` saturates (NaN → 0), like Mitsuba's UInt32 conversion of in-range values.
    let i = (x as usize).min(TABLE_RES - 2);
    let (v0, v1) = (table[i], table[i + 1]);
    v0 + (v1 - v0) * (x - i as f32)
}
