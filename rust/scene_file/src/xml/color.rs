//! Colours as Mitsuba's `scalar_rgb` variant reads them (docs/renderer-semantics.md §2,
//! `src/core/properties.cpp::get_texture_impl`, `src/spectra/srgb.cpp`,
//! `src/core/spectrum.cpp::spectrum_list_to_srgb`).

use super::cie::{
    CIE_MAX, CIE_MIN, CIE_SAMPLES, CIE_X, CIE_Y, CIE_Y_NORMALIZATION, CIE_Z, D65, D65_NORMALIZATION, XYZ_TO_SRGB,
};

/// How a plugin reads a colour property; it decides range checks and what a spectrum means.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorUse {
    /// Reflectances (`get_texture`): an `<rgb>` outside [0, 1] is an error, a sampled
    /// spectrum is weighted by D65 and clamped to [0, 1].
    Bounded,
    /// `eta`, `k`, `alpha` (`get_unbounded_texture`): no range check; a sampled spectrum is
    /// weighted by D65 and its negative channels set to 0.
    Unbounded,
    /// `radiance`, `intensity`, `irradiance` (`get_emissive_texture`): no range check; a
    /// constant spectrum becomes `v·xyz_to_srgb(1,1,1)`, a sampled one is not D65-weighted.
    Emissive,
}

/// `xyz_to_srgb(1, 1, 1)`: the colour of a flat (equal-energy) spectrum, which is not white
/// under D65 — (1.204794, 0.948291, 0.908916). Mitsuba evaluates it in `float`
/// (`Color3f(1.0)`), so the row sums are taken in `f32` to match it to the last bit.
pub(crate) fn equal_energy_rgb() -> [f64; 3] {
    XYZ_TO_SRGB.map(|row| (row[0] + row[1] + row[2]) as f64)
}

/// A constant spectrum `<spectrum value="v"/>` for `usage`.
pub(crate) fn constant_spectrum_rgb(v: f64, usage: ColorUse) -> [f64; 3] {
    match usage {
        ColorUse::Emissive => equal_energy_rgb().map(|c| v * c),
        ColorUse::Bounded | ColorUse::Unbounded => [v; 3],
    }
}

/// A wavelength-sampled spectrum `"λ:v ..."` for `usage`, as Mitsuba's RGB variants
/// pre-integrate it: reflectance-like uses weight by D65, emission does not (§2 table).
pub(crate) fn sampled_spectrum_rgb(samples: &[(f64, f64)], usage: ColorUse) -> [f64; 3] {
    spectrum_list_to_srgb(samples, usage == ColorUse::Bounded, usage != ColorUse::Emissive)
}

/// Linear interpolation of a 95-entry 5 nm table at `w` nm (0 outside [360, 830]), as
/// Mitsuba's `cie1931_xyz`/`cie_d65` do.
#[inline]
fn lerp_table(table: &[f32; CIE_SAMPLES], w: f64) -> f64 {
    if !(CIE_MIN..=CIE_MAX).contains(&w) {
        return 0.0;
    }
    let t = (w - CIE_MIN) * ((CIE_SAMPLES - 1) as f64 / (CIE_MAX - CIE_MIN));
    let i0 = (t as usize).min(CIE_SAMPLES - 2);
    let w1 = t - i0 as f64;
    (1.0 - w1) * table[i0] as f64 + w1 * table[i0 + 1] as f64
}

/// (λ nm, value) samples → linear sRGB, Mitsuba's `spectrum_list_to_srgb`: a 1000-point
/// Riemann sum over [360, 830] nm of the linearly interpolated spectrum times the CIE 1931
/// matching functions (× D65 if `d65`), skipping wavelengths outside the samples' range,
/// then XYZ → sRGB. `bounded` clamps to [0, 1], otherwise negatives are set to 0 (Mitsuba
/// warns in both cases). `samples` must be sorted by strictly increasing wavelength; fewer
/// than two samples span no interval and give black.
///
/// Public because conductor `material` presets (§10) use the same conversion with
/// `bounded = false, d65 = false`.
pub fn spectrum_list_to_srgb(samples: &[(f64, f64)], bounded: bool, d65: bool) -> [f64; 3] {
    if samples.len() < 2 {
        return [0.0; 3];
    }
    const STEPS: usize = 1000;
    let (first, last) = (samples[0].0, samples[samples.len() - 1].0);
    let mut xyz = [0.0f64; 3];
    for i in 0..STEPS {
        let w = CIE_MIN + (i as f64 / (STEPS - 1) as f64) * (CIE_MAX - CIE_MIN);
        if w < first || w > last {
            continue;
        }
        // The interval [k, k+1] with samples[k].0 <= w, clamped to a valid interval.
        let k = samples.partition_point(|s| s.0 <= w).saturating_sub(1).min(samples.len() - 2);
        let ((w0, v0), (w1, v1)) = (samples[k], samples[k + 1]);
        let v = ((w - w1) * v0 + (w0 - w) * v1) / (w0 - w1);
        let weight = if d65 { lerp_table(&D65, w) * D65_NORMALIZATION } else { 1.0 };
        let f = v * weight;
        xyz[0] += lerp_table(&CIE_X, w) * f;
        xyz[1] += lerp_table(&CIE_Y, w) * f;
        xyz[2] += lerp_table(&CIE_Z, w) * f;
    }
    let scale = (CIE_MAX - CIE_MIN) * CIE_Y_NORMALIZATION / STEPS as f64;
    let xyz = xyz.map(|c| c * scale);
    let rgb = XYZ_TO_SRGB.map(|row| row[0] as f64 * xyz[0] + row[1] as f64 * xyz[1] + row[2] as f64 * xyz[2]);
    if bounded { rgb.map(|c| c.clamp(0.0, 1.0)) } else { rgb.map(|c| c.max(0.0)) }
}
