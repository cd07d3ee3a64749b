//! EON's roughness for a simulated surface (`docs/microgeometry.md#eons-roughness`): EON's r is
//! OpenPBR's `base_diffuse_roughness`, not Oren–Nayar's σ, and the EON paper (Portsmouth et al.
//! 2025) gives no relation between them. The r that describes a measured surface best is the one
//! that minimises the mean relative error of f over the measured directions.

use glam::DVec3;
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue, Params};

/// Scan step of r over [0, 1] before the golden-section refinement.
const SCAN_STEP: f64 = 0.01;

/// Mean |f_EON(r) / f − 1| over `targets` = (wi, wo, measured f).
pub fn mean_relative_error(r: f64, targets: &[(DVec3, DVec3, f64)], reflectance: f64) -> Result<f64, String> {
    let eon = DiffuseModel::from_params("eon", Params::new().with("roughness", ParamValue::Number(r)))
        .map_err(|e| e.to_string())?;
    let rho = [reflectance as f32];
    let sum: f64 =
        targets.iter().map(|(wi, wo, f)| (eon.eval(wi.as_vec3(), wo.as_vec3(), rho)[0] as f64 / f - 1.0).abs()).sum();
    Ok(sum / targets.len().max(1) as f64)
}

/// The r ∈ [0, 1] with the smallest mean relative error: a scan in steps of 0.01, then a golden
/// section search within one step of the scan's best (to ±1e-4).
pub fn best_eon_roughness(targets: &[(DVec3, DVec3, f64)], reflectance: f64) -> Result<f64, String> {
    if targets.iter().any(|t| !(t.2 > 0.0)) {
        return Err("EON fit: every measured f must be positive".into());
    }
    let err = |r: f64| mean_relative_error(r, targets, reflectance);
    let steps = (1.0 / SCAN_STEP).round() as usize;
    let mut best = (0.0, err(0.0)?);
    for k in 1..=steps {
        let r = k as f64 * SCAN_STEP;
        let e = err(r)?;
        if e < best.1 {
            best = (r, e);
        }
    }
    let (mut a, mut b) = ((best.0 - SCAN_STEP).max(0.0), (best.0 + SCAN_STEP).min(1.0));
    let g = (5f64.sqrt() - 1.0) / 2.0;
    while b - a > 1e-4 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if err(c)? < err(d)? {
            b = d;
        } else {
            a = c;
        }
    }
    let mid = 0.5 * (a + b);
    Ok(if err(mid)? <= best.1 { mid } else { best.0 })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Targets made by EON itself at a known r are fitted back to that r.
    #[test]
    fn recovers_the_roughness_of_eon_data() {
        let dir = |t: f64, p: f64| {
            let (t, p) = (t.to_radians(), p.to_radians());
            DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
        };
        let eon = DiffuseModel::from_params("eon", Params::new().with("roughness", ParamValue::Number(0.437))).unwrap();
        let mut targets = Vec::new();
        for ti in [0.0, 30.0, 60.0, 75.0] {
            for to in [0.0, 20.0, 40.0, 60.0, 80.0] {
                for p in [0.0, 90.0, 180.0] {
                    let (wi, wo) = (dir(ti, 0.0), dir(to, p));
                    targets.push((wi, wo, eon.eval(wi.as_vec3(), wo.as_vec3(), [0.7])[0] as f64));
                }
            }
        }
        let r = best_eon_roughness(&targets, 0.7).unwrap();
        assert!((r - 0.437).abs() < 1e-3, "fitted r = {r}");
    }
}
