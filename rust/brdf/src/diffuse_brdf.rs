//! The interface every diffuse model implements: eval (f without cosine), pdf, sample and
//! directional albedo. Reflectance is passed per call and per channel because several models
//! are non-linear in it (full Oren–Nayar's ρ² term, EON's multiple scattering, Wolff's
//! physical normalisation), so an RGB or spectral caller cannot scale a grey result.

use super::quadrature::GaussLegendre;
use super::real::V3;
use super::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use glam::{DVec3, Vec2, Vec3};

/// A sampled direction with its solid-angle density and the path weight
/// `f(wi, wo) cos θo / pdf` per channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfSample<const N: usize> {
    pub wo: Vec3,
    pub pdf: f32,
    pub weight: [f32; N],
}

impl<const N: usize> BrdfSample<N> {
    /// From [`super::kernel::sample`]'s `(wo, weight, pdf)`; `None` when nothing was drawn.
    #[inline(always)]
    pub fn from_kernel((wo, weight, pdf): (V3<f32>, [f32; N], f32)) -> Option<Self> {
        (pdf > 0.0).then(|| BrdfSample { wo: wo.into(), pdf, weight })
    }
}

/// How an albedo value was obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AlbedoMethod {
    ClosedForm,
    Quadrature,
}

impl AlbedoMethod {
    pub fn as_str(self) -> &'static str {
        match self {
            AlbedoMethod::ClosedForm => "closed form",
            AlbedoMethod::Quadrature => "quadrature",
        }
    }
}

/// Directional albedo `E(wi) = ∫ f(wi, wo) cos θo dwo`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Albedo {
    pub value: f64,
    pub method: AlbedoMethod,
}

/// A diffuse BRDF in the local frame (z = normal; `wi` the given direction, towards the previous
/// vertex of a path, `wo` the other one, as in Mitsuba and the renderer: `docs/conventions.md`;
/// every model is reciprocal). One-sided: zero unless both directions are strictly above the surface.
pub trait DiffuseBrdf {
    /// `f(wi, wo)` in 1/sr, **without** the cosine, for each reflectance channel.
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N];

    /// Solid-angle density of [`Self::sample`]'s directions. Default: cosine-weighted, zero when
    /// either direction is below the surface (as Mitsuba's `diffuse`).
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        if wi.z <= 0.0 || wo.z <= 0.0 { 0.0 } else { cosine_hemisphere_pdf(wo) }
    }

    /// Draws `wo` given `wi` from two uniform numbers and returns it with its density
    /// ([`Self::pdf`]) and the weight `f cos θo / pdf` per channel; `None` when no direction can
    /// be drawn (`wi` below the surface). Default: cosine-weighted (Mitsuba's warp), the
    /// density of the default [`Self::pdf`]; a model that overrides one overrides both.
    #[inline]
    fn sample<const N: usize>(&self, wi: Vec3, u: Vec2, reflectance: [f32; N]) -> Option<BrdfSample<N>> {
        if wi.z <= 0.0 {
            return None;
        }
        let wo = square_to_cosine_hemisphere(u);
        let pdf = cosine_hemisphere_pdf(wo);
        if !(pdf > 0.0) {
            return None;
        }
        let f = self.eval(wi, wo, reflectance);
        let scale = wo.z / pdf;
        Some(BrdfSample { wo, pdf, weight: f.map(|x| x * scale) })
    }

    /// Directional albedo for a grey reflectance. Default: numerical quadrature of `eval`
    /// ([`albedo_by_quadrature`]); models with a closed form override it.
    fn albedo(&self, cos_theta_i: f64, reflectance: f32) -> Albedo {
        Albedo { value: albedo_by_quadrature(self, cos_theta_i, reflectance), method: AlbedoMethod::Quadrature }
    }
}

/// `E(wi) = ∫_0^1 ∫_0^{2π} f μo dφ dμo` by Gauss–Legendre in μo and φ, wi in the plane φ = 0.
/// The μo range is split at μi and the azimuth range at π/2 (and mirrored, f being even in
/// φ): that is where the Oren–Nayar family has kinks (`max(μi, μo)`, `max(0, cos Δφ)`), so
/// every piece is smooth and the rule converges fast (error < 1e-6 on the closed forms).
pub fn albedo_by_quadrature<B: DiffuseBrdf + ?Sized>(brdf: &B, cos_theta_i: f64, reflectance: f32) -> f64 {
    if cos_theta_i <= 0.0 {
        return 0.0;
    }
    let mu_i = cos_theta_i.min(1.0);
    let wi = DVec3::new((1.0 - mu_i * mu_i).max(0.0).sqrt(), 0.0, mu_i).as_vec3();
    let gl = GaussLegendre::new(48);
    let mut total = 0.0;
    for (mu_a, mu_b) in [(0.0, mu_i), (mu_i, 1.0)] {
        if mu_b <= mu_a {
            continue;
        }
        for (mu_o, w_mu) in gl.mapped(mu_a, mu_b) {
            let sin_o = (1.0 - mu_o * mu_o).max(0.0).sqrt();
            for (phi_a, phi_b) in
                [(0.0, std::f64::consts::FRAC_PI_2), (std::f64::consts::FRAC_PI_2, std::f64::consts::PI)]
            {
                for (phi, w_phi) in gl.mapped(phi_a, phi_b) {
                    let wo = DVec3::new(sin_o * phi.cos(), sin_o * phi.sin(), mu_o).as_vec3();
                    let f = brdf.eval(wi, wo, [reflectance])[0] as f64;
                    total += 2.0 * f * mu_o * w_mu * w_phi;
                }
            }
        }
    }
    total
}
