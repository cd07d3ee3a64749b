//! Inlinable replacements for libm functions on the kernels' per-eval path, and branch-free
//! clamps. libm's `acosf` is an out-of-line call that cannot be inlined or vectorised; in EON
//! (two per eval) and van Ginneken (one per eval) it was the largest single cost. Each
//! approximation here has a stated maximum error, checked against f64 `std` in the tests.
//! `f32::mul_add` compiles to one FMA instruction because `.cargo/config.toml` builds for
//! x86-64-v3.

use super::real::Real;
use std::f32::consts::{FRAC_PI_2, PI};

/// `max(x, lo)` as one `maxss`: `f32::max` also orders NaN against its other operand, which
/// costs a compare and a blend per call. A NaN `x` gives `lo`, as `f32::max` does.
#[inline(always)]
pub fn at_least(x: f32, lo: f32) -> f32 {
    if x > lo { x } else { lo }
}

/// `min(x, hi)` as one `minss`; a NaN `x` gives `hi`, as `f32::min` does.
#[inline(always)]
pub fn at_most(x: f32, hi: f32) -> f32 {
    if x < hi { x } else { hi }
}

/// Abramowitz & Stegun, *Handbook of Mathematical Functions* (1964), eq. 4.4.46 (from
/// Hastings, *Approximations for Digital Computers*, 1955): for `0 ≤ x ≤ 1`,
/// `acos x = √(1−x) (a0 + a1 x + … + a7 x⁷) + ε`, `|ε| ≤ 2·10⁻⁸` (the printed a0 is π/2
/// rounded to 10 digits, which makes it 2.2·10⁻⁸ at x = 0).
const ACOS_AS: [f64; 8] = [
    1.570_796_305_0,
    -0.214_598_801_6,
    0.088_978_987_4,
    -0.050_174_304_6,
    0.030_891_881_0,
    -0.017_088_125_6,
    0.006_670_090_1,
    -0.001_262_491_1,
];

/// The A&S 4.4.46 polynomial `P(x)` (so `acos x ≈ √(1−x) P(x)` on [0, 1]), by Estrin's
/// scheme: three dependent fused multiply-adds instead of Horner's seven, which shortens the
/// eval's critical path (the kernels are latency-bound: few evals fit in flight at once).
#[inline(always)]
fn acos_poly<T: Real>(x: T) -> T {
    let a = ACOS_AS.map(T::c);
    let x2 = x * x;
    let p01 = a[1].fma(x, a[0]);
    let p23 = a[3].fma(x, a[2]);
    let p45 = a[5].fma(x, a[4]);
    let p67 = a[7].fma(x, a[6]);
    let p03 = p23.fma(x2, p01);
    let p47 = p67.fma(x2, p45);
    p47.fma(x2 * x2, p03)
}

/// `acos x` for `x ∈ [0, 1]` (clamped) by A&S 4.4.46 evaluated in f32. Max absolute error
/// 3.5·10⁻⁷ (3 f32 ulps of π/2: the 2·10⁻⁸ of the fit, a0's rounding and the roundings of
/// Estrin's scheme, the square root and the product) and relative error 3·10⁻⁷
/// (`acos_matches_f64_over_the_unit_interval`). Near x = 1 the `√(1−x)` factor keeps the
/// relative error small, where `π/2 − asin` forms would cancel. (Rounding a0 to f32 puts it
/// 7.5·10⁻⁸ below π/2, so `acos_unit(0)` is one ulp below libm's `acosf(0)`.)
#[inline(always)]
pub fn acos_unit<T: Real>(x: T) -> T {
    let x = x.clamp_to(0.0, 1.0);
    (T::c(1.0) - x).sqrt() * acos_poly(x)
}

/// Abramowitz & Stegun (1964) eq. 4.4.49 (after Hastings 1955): for `0 ≤ x ≤ 1`,
/// `atan x = x (1 + a2 x² + a4 x⁴ + … + a16 x¹⁶) + ε`, `|ε| ≤ 2·10⁻⁸`.
const ATAN_AS: [f64; 9] = [
    1.0,
    -0.333_331_452_8,
    0.199_935_508_5,
    -0.142_088_994_4,
    0.106_562_639_3,
    -0.075_289_640_0,
    0.042_909_613_8,
    -0.016_165_736_7,
    0.002_866_225_7,
];

/// `atan t` for `t ∈ [0, 1]` by A&S 4.4.49 (Estrin's scheme in `t²`). Max absolute error
/// 1.5·10⁻⁷ (`atan_matches_f64_over_the_unit_interval`).
#[inline(always)]
fn atan_unit<T: Real>(t: T) -> T {
    let a = ATAN_AS.map(T::c);
    let z = t * t;
    let z2 = z * z;
    let p01 = a[1].fma(z, a[0]);
    let p23 = a[3].fma(z, a[2]);
    let p45 = a[5].fma(z, a[4]);
    let p67 = a[7].fma(z, a[6]);
    let p03 = p23.fma(z2, p01);
    let p47 = p67.fma(z2, p45);
    let p48 = a[8].fma(z2 * z2, p47);
    t * p48.fma(z2 * z2, p03)
}

/// Abramowitz & Stegun (1964) eq. 4.4.47 (after Hastings 1955): for `0 ≤ x ≤ 1`,
/// `atan x = a1 x + a3 x³ + a5 x⁵ + a7 x⁷ + a9 x⁹ + ε`, `|ε| ≤ 10⁻⁵` (1.15·10⁻⁵ with the
/// printed coefficients).
const ATAN_AS_COARSE: [f64; 5] = [0.999_866_0, -0.330_299_5, 0.180_141_0, -0.085_133_0, 0.020_835_1];

/// `atan t` for `t ∈ [0, 1]` by A&S 4.4.47: four FMAs instead of [`atan_unit`]'s eight. Max
/// absolute error 1.2·10⁻⁵ (`coarse_atan_matches_f64_over_the_unit_interval`).
#[inline(always)]
fn atan_unit_coarse<T: Real>(t: T) -> T {
    let a = ATAN_AS_COARSE.map(T::c);
    let z = t * t;
    let z2 = z * z;
    let p01 = a[1].fma(z, a[0]);
    let p24 = a[4].fma(z2, a[3].fma(z, a[2]));
    t * p24.fma(z2, p01)
}

/// The angle in `[0, π]` between the x axis and `(x, |y|)`: `atan2(|y|, x)` by
/// [`atan_unit`] of `min/max(|x|, y)` and the octant reflections. One division and no square
/// root: an angle from a dot and a cross product without forming the cosine first, whose
/// square root and division would precede an `acos` on the same dependency chain. Max absolute
/// error 4·10⁻⁷ (`angle_matches_f64_atan2_in_the_upper_half_plane`); `(0, 0)` gives 0.
#[inline(always)]
pub fn angle<T: Real>(y: T, x: T) -> T {
    angle_by(y, x, atan_unit)
}

/// [`angle`] with [`atan_unit_coarse`]: max absolute error 1.2·10⁻⁵
/// (`coarse_angle_matches_f64_atan2_in_the_upper_half_plane`). For van Ginneken's Δφ, which
/// needs no more: an error δ in Δφ moves f by at most 4.41 δ relative (the azimuth
/// correlation's slope), 5·10⁻⁵, against its tables' 10⁻³.
#[inline(always)]
pub fn angle_coarse<T: Real>(y: T, x: T) -> T {
    angle_by(y, x, atan_unit_coarse)
}

#[inline(always)]
fn angle_by<T: Real>(y: T, x: T, atan_unit: impl Fn(T) -> T) -> T {
    let (ax, ay) = (x.abs(), y.abs());
    let below_diagonal = ay.le(ax);
    let lo = T::select(below_diagonal, ay, ax);
    let hi = T::select(below_diagonal, ax, ay).max(T::c(f32::MIN_POSITIVE as f64));
    let r = atan_unit(lo / hi);
    let r = T::select(below_diagonal, r, T::c(FRAC_PI_2 as f64) - r);
    T::select(x.lt(T::c(0.0)), T::c(PI as f64) - r, r)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every f32 in [0, 1] whose bits are a multiple of `stride`, plus the end points.
    fn unit_grid(stride: u32) -> impl Iterator<Item = f32> {
        (0..=1.0f32.to_bits()).step_by(stride as usize).map(f32::from_bits).chain([0.0, 1.0])
    }

    #[test]
    fn coefficients_meet_the_published_bound_in_f64() {
        // The published bound, checked on the formula itself (f64 arithmetic): an independent
        // check that the coefficients were transcribed correctly.
        let mut worst = 0.0f64;
        for k in 0..=200_000 {
            let x = k as f64 / 200_000.0;
            let p = ACOS_AS.iter().rev().fold(0.0f64, |acc, &c| acc * x + c);
            worst = worst.max(((1.0 - x).sqrt() * p - x.acos()).abs());
        }
        assert!(worst < 2.2e-8, "max |err| = {worst:e}");
    }

    #[test]
    fn acos_matches_f64_over_the_unit_interval() {
        let (mut abs_err, mut rel_err) = (0.0f64, 0.0f64);
        for x in unit_grid(97) {
            let want = (x as f64).acos();
            let got = acos_unit(x) as f64;
            abs_err = abs_err.max((got - want).abs());
            if want > 0.0 {
                rel_err = rel_err.max((got - want).abs() / want);
            }
        }
        assert!(abs_err <= 3.5e-7, "max |err| = {abs_err:e}");
        assert!(rel_err <= 3e-7, "max relative err = {rel_err:e}");
        assert_eq!(acos_unit(1.0), 0.0);
    }

    #[test]
    fn atan_coefficients_meet_the_published_bound_in_f64() {
        let mut worst = 0.0f64;
        for k in 0..=200_000 {
            let t = k as f64 / 200_000.0;
            let p = ATAN_AS.iter().rev().fold(0.0f64, |acc, &c| acc * t * t + c);
            worst = worst.max((t * p - t.atan()).abs());
        }
        assert!(worst <= 2e-8, "max |err| = {worst:e}");
    }

    /// Largest |atan_fn(t) − atan t| over the unit interval (f64 reference).
    fn worst_atan_error(atan_fn: impl Fn(f32) -> f32) -> f64 {
        unit_grid(97).map(|t| (atan_fn(t) as f64 - (t as f64).atan()).abs()).fold(0.0, f64::max)
    }

    /// `angle_fn` against f64 `atan2` on a fine half circle at radii from 1e-20 to 1e20 (the
    /// ratio is what counts), within `bound`, and exact where both operands are on an axis.
    fn assert_angle_matches_atan2(angle_fn: impl Fn(f32, f32) -> f32, bound: f64) {
        let mut worst = 0.0f64;
        for k in 0..=100_000 {
            let phi = std::f64::consts::PI * k as f64 / 100_000.0;
            for r in [1e-20f64, 1e-3, 1.0, 7.5, 1e20] {
                let (x, y) = ((r * phi.cos()) as f32, (r * phi.sin()).max(0.0) as f32);
                worst = worst.max((angle_fn(y, x) as f64 - (y as f64).atan2(x as f64)).abs());
            }
        }
        assert!(worst <= bound, "max |err| = {worst:e}");
        assert_eq!(angle_fn(0.0, 0.0), 0.0);
        assert_eq!(angle_fn(0.0, 1.0), 0.0);
        assert!((angle_fn(0.0, -1.0) - PI).abs() <= 2.4e-7);
        assert!((angle_fn(1.0, 0.0) - FRAC_PI_2).abs() <= 1.2e-7);
    }

    #[test]
    fn atan_matches_f64_over_the_unit_interval() {
        let worst = worst_atan_error(atan_unit);
        assert!(worst <= 1.5e-7, "max |err| = {worst:e}");
    }

    #[test]
    fn angle_matches_f64_atan2_in_the_upper_half_plane() {
        assert_angle_matches_atan2(angle, 4e-7);
    }

    #[test]
    fn coarse_atan_matches_f64_over_the_unit_interval() {
        let worst = worst_atan_error(atan_unit_coarse);
        // A&S state 1e-5; their printed seven-digit coefficients reach 1.15e-5.
        assert!(worst <= 1.2e-5, "max |err| = {worst:e}");
    }

    #[test]
    fn coarse_angle_matches_f64_atan2_in_the_upper_half_plane() {
        assert_angle_matches_atan2(angle_coarse, 1.2e-5);
    }

    #[test]
    fn clamps_agree_with_std_including_nan() {
        for x in [f32::NAN, f32::NEG_INFINITY, -1.0, -0.0, 0.0, 1e-30, 0.5, 1.0, 2.0, f32::INFINITY] {
            for b in [-1.0f32, 0.0, 1e-7, 1.0] {
                // == rather than bits: the sign of a zero result may differ, which no caller sees.
                assert!(at_least(x, b) == x.max(b), "at_least({x}, {b})");
                assert!(at_most(x, b) == x.min(b), "at_most({x}, {b})");
            }
        }
    }
}
