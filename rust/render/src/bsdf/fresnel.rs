//! Fresnel reflectance of smooth interfaces as Mitsuba 3.9.1 evaluates it
//! (`include/mitsuba/render/fresnel.h`): the dielectric version for both sides of the
//! interface (it also gives the refracted cosine and the relative indices the caller needs),
//! and the conductor version with a complex index `η + i·k`, per RGB channel.
//!
//! `brdf::fresnel::dielectric_reflectance` is one-sided (light always arrives from the side of
//! index 1, `cos θ` clamped to [0, 1]), so the renderer's glass uses [`fresnel_dielectric`]
//! instead; the two agree where both apply (`tests/render/specular_bsdfs.rs`).

use glam::Vec3;

/// Result of [`fresnel_dielectric`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DielectricFresnel {
    /// Unpolarized reflectance R (1 under total internal reflection and at `cos θi = 0`,
    /// 0 for an index-matched interface).
    pub r: f32,
    /// Cosine of the refracted direction, signed **opposite** to `cos θi` (it is on the other
    /// side); 0 under total internal reflection.
    pub cos_t: f32,
    /// Relative index in the direction of travel, η_t/η_i (Mitsuba `eta_it`).
    pub eta_it: f32,
    /// Its reciprocal η_i/η_t, also the scale of the tangential part of the refracted
    /// direction (Mitsuba `eta_ti`).
    pub eta_ti: f32,
}

/// Mitsuba's `fresnel(cos_theta_i, eta)`: `eta` = η_int/η_ext > 0; `cos_i ≥ 0` means the
/// incident direction is on the exterior side (the normal's side), `cos_i < 0` inside.
#[inline]
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> DielectricFresnel {
    let outside = cos_i >= 0.0;
    let (eta_it, eta_ti) = if outside { (eta, eta.recip()) } else { (eta.recip(), eta) };
    // Snell: sin²θt = sin²θi · (η_i/η_t)²; negative cos²θt means total internal reflection.
    let cos_t_sqr = 1.0 - (1.0 - cos_i * cos_i) * (eta_ti * eta_ti);
    let ci = cos_i.abs();
    let ct = cos_t_sqr.max(0.0).sqrt();
    // s- and p-polarized amplitude ratios; at TIR (ct = 0) they are ±1, so r = 1 there.
    let a_s = (ci - eta_it * ct) / (ci + eta_it * ct);
    let a_p = (ct - eta_it * ci) / (ct + eta_it * ci);
    let r = 0.5 * (a_s * a_s + a_p * a_p);
    // Index-matched: no interface. Grazing: 0/0 above, the limit is total reflection.
    let r = if eta == 1.0 {
        0.0
    } else if ci == 0.0 {
        1.0
    } else {
        r
    };
    DielectricFresnel { r, cos_t: if outside { -ct } else { ct }, eta_it, eta_ti }
}

/// Unpolarized reflectance of a conductor with complex relative index `eta + i·k` per RGB
/// channel, for light arriving from outside at `cos_i` (Mitsuba's `fresnel_conductor`, after
/// Moeller, *Optics*; exact, not Schlick). `cos_i` is clamped to [0, 1]; a vanishing
/// denominator (η = 1, k = 0 at grazing, or η = k = 0 at normal incidence) gives the limit 1
/// instead of 0/0, so the result is finite for every finite input.
#[inline]
pub fn fresnel_conductor(cos_i: f32, eta: Vec3, k: Vec3) -> Vec3 {
    Vec3::new(
        fresnel_conductor_1(cos_i, eta.x, k.x),
        fresnel_conductor_1(cos_i, eta.y, k.y),
        fresnel_conductor_1(cos_i, eta.z, k.z),
    )
}

/// One channel of [`fresnel_conductor`].
#[inline]
fn fresnel_conductor_1(cos_i: f32, eta: f32, k: f32) -> f32 {
    let c = cos_i.clamp(0.0, 1.0);
    let c2 = c * c;
    let s2 = 1.0 - c2;
    // n² − sin²θ = (η² − k² − sin²θ) + i·2ηk; `a2_plus_b2` is its modulus, `a` the real part
    // of its square root.
    let re = eta * eta - k * k - s2;
    let a2_plus_b2 = (re * re + 4.0 * eta * eta * k * k).sqrt();
    let a = (0.5 * (a2_plus_b2 + re)).max(0.0).sqrt();
    let t1 = a2_plus_b2 + c2;
    let t2 = 2.0 * c * a;
    let r_s = ratio_or_one(t1 - t2, t1 + t2);
    let t3 = a2_plus_b2 * c2 + s2 * s2;
    let t4 = t2 * s2;
    let r_p = r_s * ratio_or_one(t3 - t4, t3 + t4);
    0.5 * (r_s + r_p)
}

/// `num/den` for the non-negative denominators above, 1 where the denominator vanishes.
#[inline]
fn ratio_or_one(num: f32, den: f32) -> f32 {
    if den > 0.0 { num / den } else { 1.0 }
}
