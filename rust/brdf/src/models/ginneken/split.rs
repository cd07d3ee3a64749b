//! What both van Ginneken kernels share (one roughness's tables, `GinnekenKernel`, and the
//! tables over m, `roughness_axis::GinnekenAxisKernel`): how the slope integral's split
//! `I = rest / (1 − r)` and μΛ are looked up ([`SlopeSplit`]), `π f` from that split
//! ([`reduced_with`]), and the fitted importance sampler.

use super::shadowing::{Shadowing, visibility_fraction};
use super::table::{SlopeGeometry, axis_of_cos};
use crate::approx;
use crate::cltc::ClippedLtc;
use crate::kernel::azimuthal_dot;
use crate::real::{Real, V3};
use crate::sampler_fits::GINNEKEN;

/// Cosines are clamped to this before entering `1/(μi μo)`-type terms: f stays finite (the
/// model's back-scattering peak grows like 1/μ at grazing) without affecting any angle a
/// renderer can resolve.
pub(crate) const MIN_COS: f32 = 1e-7;

/// The sampler's roughness variable `t = (m/(1 + m))/0.8` ∈ (0, 1] for m ∈ (0, 4]: the
/// roughness axis of the per-lane tables ([`super::roughness_axis`]), scaled to 1 at m = 4.
#[inline(always)]
pub fn sampler_roughness<T: Real>(m: T) -> T {
    (m / (m + T::c(1.0))).scale(1.25)
}

/// The importance sampler at `μ = cos θi` and roughness variable `t`
/// ([`sampler_roughness`]): the CLTC fitted to the model (`rust/brdf/src/sampler_fits.rs`,
/// `validation/generators/fit_samplers.py`), polynomial in μ and t, no table; the cosine at t = 0. One
/// fit serves both shadowing options (fitted to each, they differ by 2–3 % in variance).
#[inline(always)]
pub fn sampler<T: Real>(mu: T, t: T) -> ClippedLtc<T> {
    GINNEKEN.sampler(mu, t)
}

/// How a kernel looks up the slope integral's split `I = rest / (1 − r)` ([`super::table`]) and μΛ:
/// one roughness's tables ([`super::GinnekenKernel`]) or tables over m too
/// ([`super::roughness_axis::GinnekenAxisKernel`]). A trait rather than a closure so that the lookup
/// is inlined into the kernel (a closure this size was called out of line).
pub(crate) trait SlopeSplit<T: Real> {
    /// Per direction, `([P0/μ², P1/μ³, H/μ], μΛ)`.
    fn directions(&self, g: &SlopeGeometry<T>) -> [([T; 3], T); 2];
    /// The wedge ratio `r = K/I`.
    fn ratio(&self, g: &SlopeGeometry<T>) -> T;
}

/// `π f` given how the slope integral's split `I = rest / (1 − r)` and μΛ are looked up
/// ([`SlopeSplit`]).
#[inline(always)]
pub(crate) fn reduced_with<T: Real, const N: usize>(
    shadowing: Shadowing,
    wi: V3<T>,
    wo: V3<T>,
    rho: [T; N],
    split: &impl SlopeSplit<T>,
) -> [T; N] {
    // Only the lower clamp matters (a cosine a rounding above 1 changes nothing); NaN gives MIN_COS.
    let (mu_i, mu_o) = (wi.z.max(T::c(MIN_COS as f64)), wo.z.max(T::c(MIN_COS as f64)));
    // s = wi·wo − μi μo = sin θi sin θo cos Δφ, with the sines from the directions' xy. Δφ
    // (for the ratio table and the visibility) is the angle of (s, c) with c = (wi × wo)·z,
    // since s² + c² = sin²θi sin²θo: no division by the sines and no acos; (0, 0) gives 0.
    let s = azimuthal_dot(wi, wo);
    let (sin_i, sin_o) = ((wi.x * wi.x + wi.y * wi.y).sqrt(), (wo.x * wo.x + wo.y * wo.y).sqrt());
    let phi = approx::angle_coarse(wi.x * wo.y - wi.y * wo.x, s);
    let geometry = SlopeGeometry {
        mu: [mu_i, mu_o],
        sin: [sin_i, sin_o],
        x: [axis_of_cos(mu_i, sin_i), axis_of_cos(mu_o, sin_o)],
        // ≥ 0 exactly; the clamp removes the rounding of s ≈ −si so at Δφ ≈ π.
        sin_sum: sin_i.fma(sin_o, s).max(T::c(0.0)),
        phi,
    };
    let [(fi, ml_i), (fo, ml_o)] = split.directions(&geometry);
    let (num, den) = visibility_fraction(shadowing, mu_i, mu_o, ml_i, ml_o, phi);
    let rest = geometry.rest(fi, fo);
    let g = (rest * num) / (den * (T::c(1.0) - split.ratio(&geometry)));
    rho.map(|r| r * g)
}
