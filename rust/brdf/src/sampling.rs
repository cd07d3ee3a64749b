//! Cosine-weighted hemisphere sampling, written to reproduce Mitsuba 3.9.1's
//! `warp::square_to_cosine_hemisphere` (Shirley–Chiu concentric disk map with Dave Cline's
//! branch-reduced form, `include/mitsuba/core/warp.h`) so that `lambert` draws the same
//! directions as Mitsuba's built-in `diffuse` for the same sample inputs.
//!
//! Bit-for-bit agreement needs the same sine and cosine too: Dr.Jit does not call libm but
//! evaluates the Cephes single-precision approximation (Moshier, Cephes `sinf.c`: Cody–Waite
//! reduction by π/4 in three parts, degree-7/8 minimax polynomials). libm's `sinf` differs
//! from it by an ulp here and there, and z = √(1 − x² − y²) amplifies that near the disk's
//! rim (measured: 4e-6 relative in z); with [`sincos_cephes`] the samples are identical
//! (`tests/plugin/test_lambert_vs_diffuse.py`).

use super::real::{Real, V3};
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4};

/// Uniform disk sample from the unit square (concentric map), in any [`Real`]: the same
/// operations, in the same order, as Mitsuba's `warp::square_to_uniform_disk_concentric`.
#[inline(always)]
pub fn concentric_disk<T: Real>(u1: T, u2: T) -> (T, T) {
    let x = T::c(2.0).fma(u1, T::c(-1.0));
    let y = T::c(2.0).fma(u2, T::c(-1.0));
    // Selects rather than branches (the quadrant is random per sample), as Dr.Jit does.
    let quadrant_1_or_3 = x.abs().lt(y.abs());
    let r = T::select(quadrant_1_or_3, y, x);
    let rp = T::select(quadrant_1_or_3, x, y);
    let phi = T::c(FRAC_PI_4 as f64) * rp / r;
    let phi = T::select(quadrant_1_or_3, T::c(FRAC_PI_2 as f64) - phi, phi);
    let phi = T::select(x.eq(T::c(0.0)) & y.eq(T::c(0.0)), T::c(0.0), phi);
    let (s, c) = phi.sincos();
    (r * c, r * s)
}

/// [`concentric_disk`] for the renderer's f32 vectors.
#[inline]
pub fn square_to_uniform_disk_concentric(u: Vec2) -> Vec2 {
    let (x, y) = concentric_disk(u.x, u.y);
    Vec2::new(x, y)
}

/// `(sin x, cos x)` for |x| ≤ 8192 by the Cephes single-precision scheme, evaluated in the
/// order Dr.Jit uses (polynomials by Estrin's scheme with fused multiply-adds).
#[inline]
pub fn sincos_cephes(x: f32) -> (f32, f32) {
    let xa = x.abs();
    // Octant index, rounded up to even so that y ∈ [−π/4, π/4].
    // Wrapping: for |x| beyond the range (∞, NaN) the saturated index must not trap in debug
    // builds; the result there is NaN either way.
    let j = ((xa * 1.273_239_5) as i32).wrapping_add(1) & !1;
    let y = j as f32;
    // Sign bits: sin flips for octants 4–7 and negative x; cos for octants 2–5.
    let sign_sin = ((j << 29) as u32 ^ x.to_bits()) & 0x8000_0000;
    let sign_cos = ((!j.wrapping_sub(2)) << 29) as u32 & 0x8000_0000;
    // Cody–Waite: π/4 = 0.78515625 + 2.4187564849853515625e-4 + 3.77489497744594108e-8.
    let y = xa - y * 0.785_156_25 - y * 2.418_756_5e-4 - y * 3.774_895e-8;
    let z = y * y;
    let z2 = z * z;
    let s = z2.mul_add(-1.951_529_6e-4, z.mul_add(8.332_161e-3, -1.666_665_5e-1)) * z;
    let c = z2.mul_add(2.443_315_7e-5, z.mul_add(-1.388_731_6e-3, 4.166_664_6e-2)) * z;
    let s = s.mul_add(y, y);
    let c = c.mul_add(z, z.mul_add(-0.5, 1.0));
    let (sv, cv) = if j & 2 == 0 { (s, c) } else { (c, s) };
    (f32::from_bits(sv.to_bits() ^ sign_sin), f32::from_bits(cv.to_bits() ^ sign_cos))
}

/// Cosine-weighted direction in the upper hemisphere, in any [`Real`]; density
/// [`cosine_pdf`].
#[inline(always)]
pub fn cosine_hemisphere<T: Real>(u1: T, u2: T) -> V3<T> {
    let (x, y) = concentric_disk(u1, u2);
    // `1 − squared_norm(p)` in the operation order of the backend ([`Real::squared_norm_2d`]):
    // the unfused sum differs from the scalar plugin's in 9 % of 2·10^4 inputs (and is what
    // the wheel's Python binding `mi.warp.square_to_cosine_hemisphere` computes: the
    // compilations differ).
    let z = (T::c(1.0) - T::squared_norm_2d(x, y)).safe_sqrt();
    V3::new(x, y, z)
}

/// Solid-angle density of [`cosine_hemisphere`] for a direction with `cos θ = z > 0`: `z/π`.
#[inline(always)]
pub fn cosine_pdf<T: Real>(z: T) -> T {
    z * T::c(std::f64::consts::FRAC_1_PI)
}

/// [`cosine_hemisphere`] for the renderer's f32 vectors.
#[inline]
pub fn square_to_cosine_hemisphere(u: Vec2) -> Vec3 {
    cosine_hemisphere(u.x, u.y).into()
}

/// Solid-angle density of [`square_to_cosine_hemisphere`]: `max(0, cos θ)/π`.
#[inline]
pub fn cosine_hemisphere_pdf(w: Vec3) -> f32 {
    FRAC_1_PI * w.z.max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cephes_sincos_is_accurate() {
        let mut worst = 0.0f64;
        for k in -100_000..=100_000 {
            let x = k as f32 * 1e-4 * std::f32::consts::PI; // [−π, π] and a bit beyond
            let (s, c) = sincos_cephes(x);
            let (es, ec) = (x as f64).sin_cos();
            worst = worst.max((s as f64 - es).abs()).max((c as f64 - ec).abs());
        }
        assert!(worst < 2e-7, "max abs error {worst}");
    }
}
