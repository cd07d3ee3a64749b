//! Sampling the distribution of visible normals D_wi(m) = G1(wi, m)·max(0, wi·m)·D(m)/cos θi
//! (Heitz & d'Eon 2014), the default of Mitsuba's `roughconductor` (`sample_visible` true,
//! `include/mitsuba/render/microfacet.h`). Both samplers use the stretch invariance: scale wi
//! by (αu, αv, 1), sample the α = 1 configuration, and scale the sampled slopes back.
//!
//! Only the density has to match Mitsuba, not the warp: GGX uses Heitz's 2018 hemisphere
//! construction; Beckmann inverts the exact α = 1 slope CDF with a bracketed Newton solve
//! (Mitsuba takes three unguarded Newton steps from the θ = 90° closed form). Both sample the *exact*
//! Smith visible-normal density; for Beckmann Mitsuba's pdf uses the rational G1 fit, so its
//! pdf is that density times a factor within 0.35 % of 1 that depends on wi only — the same
//! in Mitsuba.

use glam::{Vec2, Vec3};
use matte_brdf::sampling::square_to_uniform_disk_concentric;

/// 1/√π
const INV_SQRT_PI: f32 = 0.564_189_6;

/// GGX visible normal (Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4),
/// 2018): in the stretched frame the visible normals are those of a hemisphere seen from
/// `wi`, i.e. a uniformly sampled disk projected along `wi`; the disk's lower half is
/// foreshortened by (1 + cos θ)/2.
#[inline]
pub fn sample_ggx(wi: Vec3, alpha_u: f32, alpha_v: f32, u: Vec2) -> Vec3 {
    let v = Vec3::new(alpha_u * wi.x, alpha_v * wi.y, wi.z).normalize();
    // Orthonormal basis (t1, t2, v) with t1 horizontal; any t1 at normal incidence.
    let len2 = v.x * v.x + v.y * v.y;
    let t1 = if len2 > 0.0 { Vec3::new(-v.y, v.x, 0.0) * len2.sqrt().recip() } else { Vec3::X };
    let t2 = v.cross(t1);
    let p = square_to_uniform_disk_concentric(u);
    let s = 0.5 * (1.0 + v.z);
    let p_y = (1.0 - s) * (1.0 - p.x * p.x).max(0.0).sqrt() + s * p.y;
    let p_z = (1.0 - p.x * p.x - p_y * p_y).max(0.0).sqrt();
    let n = p.x * t1 + p_y * t2 + p_z * v;
    // Unstretch (normals transform with the inverse transpose).
    Vec3::new(alpha_u * n.x, alpha_v * n.y, n.z.max(0.0)).normalize_or_zero()
}

/// Beckmann visible normal. For α = 1 and wi in the xz-plane at angle θ, the visible slopes
/// (x̃, ỹ) of m = (−x̃, −ỹ, 1)/‖·‖ have density ∝ (1 − x̃·tan θ)·exp(−x̃² − ỹ²) for x̃ < cot θ:
/// ỹ is Gaussian, and x̃ has the CDF ∝ 1 + erf x̃ + tan θ/√π·exp(−x̃²), inverted here in the
/// variable s = erf x̃.
#[inline]
pub fn sample_beckmann(wi: Vec3, alpha_u: f32, alpha_v: f32, u: Vec2) -> Vec3 {
    let v = Vec3::new(alpha_u * wi.x, alpha_v * wi.y, wi.z).normalize();
    let sin_t = (v.x * v.x + v.y * v.y).sqrt();
    let (cos_phi, sin_phi) = if sin_t > 0.0 { (v.x / sin_t, v.y / sin_t) } else { (1.0, 0.0) };
    // Keep the inverse-erf arguments off ±1 (Mitsuba clamps the same way).
    let u = u.clamp(Vec2::splat(1e-6), Vec2::splat(1.0 - 1e-6));
    let sx = visible_slope_x(v.z, sin_t, u.x);
    let sy = erf_inv(2.0 * u.y - 1.0);
    // Rotate to wi's azimuth and unstretch.
    let x = (cos_phi * sx - sin_phi * sy) * alpha_u;
    let y = (sin_phi * sx + cos_phi * sy) * alpha_v;
    Vec3::new(-x, -y, 1.0).normalize_or_zero()
}

/// Solves C(s) = 1 + s + tan θ/√π·exp(−erf⁻¹(s)²) = u·C(s_max), s_max = erf(cot θ), for the
/// stretched incidence (cos θ, sin θ); returns the slope erf⁻¹(s). C is increasing and
/// concave on (−1, s_max], so Newton converges monotonically from the left of the root; the
/// bracket [lo, hi] catches the first step from the right (the tangent can be nearly flat at
/// s_max) and keeps every iterate inside the domain.
#[inline]
fn visible_slope_x(cos_t: f32, sin_t: f32, u: f32) -> f32 {
    let tan_t = sin_t / cos_t;
    let cot_t = cos_t / sin_t; // +∞ at normal incidence: erf(∞) = 1, exp(−∞) = 0
    let c = tan_t * INV_SQRT_PI;
    let s_max = libm::erff(cot_t);
    let tail = if cot_t.is_finite() { c * (-cot_t * cot_t).exp() } else { 0.0 };
    let target = u * (1.0 + s_max + tail);
    if !(s_max >= -1.0 && target.is_finite()) {
        // Degenerate incidence (NaN or zero-length wi): a slope whose normal has pdf 0.
        return 0.0;
    }
    let (mut lo, mut hi) = (-1.0f32, s_max);
    // The root of C without its (non-negative) exp term lies at or right of the true root.
    let mut s = (target - 1.0).clamp(lo, hi);
    for _ in 0..12 {
        let x = erf_inv(s);
        let g = 1.0 + s + c * (-x * x).exp() - target;
        if g == 0.0 {
            break;
        }
        if g > 0.0 {
            hi = s;
        } else {
            lo = s;
        }
        let next = s - g / (1.0 - x * tan_t);
        // Inclusive: Newton may land exactly on a bracket end that is the root.
        let next = if next >= lo && next <= hi { next } else { 0.5 * (lo + hi) };
        let done = (next - s).abs() <= 1e-7;
        s = next;
        if done {
            break;
        }
    }
    erf_inv(s)
}

/// Inverse error function in single precision (Giles, "Approximating the erfinv function",
/// GPU Computing Gems 2011, single-precision branch: relative error ≲ 4e-7 on (−1, 1)).
#[inline]
pub fn erf_inv(x: f32) -> f32 {
    let w = -((1.0 - x) * (1.0 + x)).ln();
    let p = if w < 5.0 {
        let w = w - 2.5;
        let mut p: f32 = 2.810_226_4e-8;
        for c in [
            3.432_739_4e-7,
            -3.523_387_7e-6,
            -4.391_506_5e-6,
            2.185_808_7e-4,
            -1.253_725e-3,
            -4.177_681_6e-3,
            0.246_640_73,
            1.501_409_4,
        ] {
            p = p.mul_add(w, c);
        }
        p
    } else {
        let w = w.sqrt() - 3.0;
        let mut p: f32 = -2.002_142_6e-4;
        for c in [
            1.009_505_6e-4,
            1.349_343_2e-3,
            -3.673_428_4e-3,
            5.739_507_7e-3,
            -7.622_461e-3,
            9.438_870_5e-3,
            1.001_674,
            2.832_976_8,
        ] {
            p = p.mul_add(w, c);
        }
        p
    };
    p * x
}
