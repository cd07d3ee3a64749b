//! What every model's evaluation shares, written once over [`Real`]: the one-sided mask,
//! Mitsuba's `eval_pdf` convention and the sampling weight. A model supplies its reduced BRDF
//! `π f` ([`Kernel::reduced_f`]) and, where it has one, its own direction sampler
//! ([`Kernel::sample_wo`] / [`Kernel::pdf_wo`]; the default is cosine-weighted). With cosine
//! sampling the weight `f cos θo / pdf` is exactly `π f` (cosine and `1/π` cancel
//! analytically), so `lambert`'s weight is `ρ` exactly, as Mitsuba's `diffuse` returns.

use super::cltc::ClippedLtc;
use super::real::{Real, V3};
use super::sampling::{cosine_hemisphere, cosine_pdf};
use std::f64::consts::FRAC_1_PI;

/// A model's evaluation with its parameter-derived constants in `T`.
pub trait Kernel<T: Real> {
    /// `π f(wi, wo)` per reflectance channel, for directions both strictly above the surface
    /// (callers mask the others). Must be finite for every input, including the masked ones.
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N];

    /// The model's own sampler (`docs/sampling.md`): the clipped LTC fitted to the model, as a
    /// function of μ = cos θi ∈ [0, 1], when the kernel samples with it; `None` (the default)
    /// for the cosine-weighted sampler. The one sampling hook a model implements: the three
    /// methods below follow it. Which sampler is known when the kernel is built (and traced).
    #[inline(always)]
    fn fitted_sampler(&self) -> Option<impl Fn(T) -> ClippedLtc<T>> {
        None::<fn(T) -> ClippedLtc<T>>
    }

    /// Whether [`Self::sample_wo`] is the default cosine-weighted sampler: the sampling weight
    /// is then `π f` itself, with no division by the pdf. Not a value of `T`: known when
    /// the kernel is built (and when it is traced).
    #[inline(always)]
    fn cosine_sampling(&self) -> bool {
        self.fitted_sampler().is_none()
    }

    /// Draws `wo` for `wi` strictly above the surface from two uniform numbers: `(wo, pdf)`:
    /// [`Self::fitted_sampler`]'s, else cosine-weighted (Mitsuba's warp). Must be finite for
    /// every input (callers mask `wi` at or below the horizon, and `wo` at or below it or with
    /// a zero pdf).
    #[inline(always)]
    fn sample_wo(&self, wi: V3<T>, u1: T, u2: T) -> (V3<T>, T) {
        match self.fitted_sampler() {
            Some(ltc) => ltc(wi.z.clamp_to(0.0, 1.0)).sample(wi, u1, u2),
            None => {
                let wo = cosine_hemisphere(u1, u2);
                (wo, cosine_pdf(wo.z))
            }
        }
    }

    /// Solid-angle density of [`Self::sample_wo`] at `wo`, for both directions strictly above
    /// the surface (callers mask the others). Must be finite for every input.
    #[inline(always)]
    fn pdf_wo(&self, wi: V3<T>, wo: V3<T>) -> T {
        match self.fitted_sampler() {
            Some(ltc) => ltc(wi.z.clamp_to(0.0, 1.0)).pdf(wi, wo),
            None => cosine_pdf(wo.z),
        }
    }
}

impl<T: Real, K: Kernel<T> + ?Sized> Kernel<T> for &K {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        (**self).reduced_f(wi, wo, rho)
    }

    #[inline(always)]
    fn cosine_sampling(&self) -> bool {
        (**self).cosine_sampling()
    }

    #[inline(always)]
    fn sample_wo(&self, wi: V3<T>, u1: T, u2: T) -> (V3<T>, T) {
        (**self).sample_wo(wi, u1, u2)
    }

    #[inline(always)]
    fn pdf_wo(&self, wi: V3<T>, wo: V3<T>) -> T {
        (**self).pdf_wo(wi, wo)
    }
}

/// Both directions strictly above the surface: every matte model is one-sided.
#[inline(always)]
pub fn both_above<T: Real>(wi: V3<T>, wo: V3<T>) -> T::Mask {
    wi.z.gt(T::c(0.0)) & wo.z.gt(T::c(0.0))
}

/// `f(wi, wo)` in 1/sr, without the cosine; 0 unless both directions are above.
#[inline(always)]
pub fn eval<T: Real, K: Kernel<T>, const N: usize>(k: &K, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
    let above = both_above(wi, wo);
    if T::none(above) {
        return [T::c(0.0); N];
    }
    let h = k.reduced_f(wi, wo, rho);
    h.map(|x| T::select(above, x * T::c(FRAC_1_PI), T::c(0.0)))
}

/// The density of [`sample`]'s directions at `wo`; 0 unless both directions are above.
#[inline(always)]
pub fn pdf<T: Real, K: Kernel<T>>(k: &K, wi: V3<T>, wo: V3<T>) -> T {
    let above = both_above(wi, wo);
    if T::none(above) {
        return T::c(0.0);
    }
    T::select(above, k.pdf_wo(wi, wo), T::c(0.0))
}

/// Mitsuba's `eval_pdf`: `(f cos θo per channel, pdf of the model's sampler)`, both 0 unless
/// both directions are above. `(ρ·(1/π))·cos θo` for Lambert: the operations of `diffuse`.
#[inline(always)]
pub fn eval_cos_pdf<T: Real, K: Kernel<T>, const N: usize>(k: &K, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> ([T; N], T) {
    let above = both_above(wi, wo);
    if T::none(above) {
        return ([T::c(0.0); N], T::c(0.0));
    }
    let f = eval(k, wi, wo, rho);
    (f.map(|x| x * wo.z), T::select(above, k.pdf_wo(wi, wo), T::c(0.0)))
}

/// A sample of the model's sampler: `(wo, weight = f cos θo / pdf per channel, pdf)`. Weight
/// and pdf are 0 when nothing can be drawn (`wi` at or below the horizon, `wo` at or below it,
/// or a zero pdf).
#[inline(always)]
pub fn sample<T: Real, K: Kernel<T>, const N: usize>(
    k: &K,
    wi: V3<T>,
    u1: T,
    u2: T,
    rho: [T; N],
) -> (V3<T>, [T; N], T) {
    let zero = T::c(0.0);
    if T::none(wi.z.gt(zero)) {
        return (V3::new(zero, zero, zero), [zero; N], zero);
    }
    let (wo, pdf) = k.sample_wo(wi, u1, u2);
    let valid = wi.z.gt(zero) & wo.z.gt(zero) & pdf.gt(zero);
    let h = k.reduced_f(wi, wo, rho);
    let weight = if k.cosine_sampling() {
        h
    } else {
        // f cos θo / pdf = π f · (cos θo / π) / pdf; the guarded pdf keeps masked lanes finite.
        let scale = wo.z * T::c(FRAC_1_PI) / pdf.max(T::c(f64::from(f32::MIN_POSITIVE)));
        h.map(|x| x * scale)
    };
    (wo, weight.map(|x| T::select(valid, x, zero)), T::select(valid, pdf, zero))
}

/// `wi·wo − μi μo = sin θi sin θo cos Δφ`: the trig-free azimuthal term of the Oren–Nayar
/// family (Oren & Nayar 1994, eq. 30 rewritten without angles).
#[inline(always)]
pub fn azimuthal_dot<T: Real>(wi: V3<T>, wo: V3<T>) -> T {
    wi.x * wo.x + wi.y * wo.y
}
