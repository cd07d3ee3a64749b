//! The simulated surface as a table (`docs/microgeometry.md#the-tabulated-ground-truth-brdf`):
//! the gonioreflectometer's f on every (θi, θo, Δφ) node and every facet-reflectance node in
//! one set of paths per θi ([`measure_reflectances`]), pooled over the surface's realisations,
//! made reciprocal by averaging f(θi, θo) with f(θo, θi), and stored as `f/ρ` in a
//! [`BrdfTable`].

use super::gonioreflectometer::{Bounces, Setup, measure_reflectances};
use super::realisations::pool;
use super::surface::MicroSurface;
use glam::DVec3;
use matte_brdf::DiffuseBrdf;
use matte_brdf::frame::spherical_direction_f64;
use matte_brdf::tabulated::{BrdfTable, TABLE_DELTA_PHI, TABLE_REFLECTANCE, TABLE_THETA};

/// The reflectance a ρ = 0 node is measured at: `f/ρ` is its limit, the single-scattering
/// BRDF of a white surface.
const SMALLEST_REFLECTANCE: f64 = 1e-6;

/// What the table build found besides the table.
#[derive(Debug, serde::Serialize)]
pub struct TableReport {
    /// Largest `E(θi)/ρ` of the interpolated table before matching the measured albedo.
    pub max_albedo_over_reflectance_before_matching: f64,
    /// The same after matching (≤ 1 up to the quadrature's and the interpolation's error).
    pub max_albedo_over_reflectance: f64,
    /// Factor applied to every entry so that `E/ρ ≤ 1` (1 when none was needed).
    pub energy_scale: f64,
    /// Mean and largest 99 % half-width relative to the value (all bounces, over the table).
    pub mean_relative_half_width: f64,
    pub max_relative_half_width: f64,
    /// The table's `E(θi)` at ρ = 1 on the θi nodes after rescaling (the furnace: 1 exactly for
    /// the surface itself, so the departure is the table's interpolation error plus noise).
    pub white_albedo: Vec<[f64; 2]>,
}

/// Tabulates the BRDF of `realisations` (one or more independent draws of the same random
/// surface; photons per θi node are split equally between them).
pub fn tabulate<S: MicroSurface>(
    realisations: &[S],
    description: &str,
    photons: u64,
    seed: u64,
) -> Result<(BrdfTable, TableReport), String> {
    if realisations.is_empty() {
        return Err("tabulation needs at least one surface realisation".into());
    }
    let per = photons / realisations.len() as u64;
    if per < 2 {
        return Err(format!("{photons} photons cannot be split over {} realisations", realisations.len()));
    }
    let (nt, np, nr) = (TABLE_THETA.len(), TABLE_DELTA_PHI.len(), TABLE_REFLECTANCE.len());
    let rhos: Vec<f64> = TABLE_REFLECTANCE.iter().map(|r| r.max(SMALLEST_REFLECTANCE)).collect();
    let wo: Vec<DVec3> = TABLE_THETA
        .iter()
        .flat_map(|&t| TABLE_DELTA_PHI.map(|p| spherical_direction_f64(t.to_radians(), p.to_radians())))
        .collect();
    // raw[r][i][o·np + p] = (mean, half-width) of f/ρ; albedo[r][i] = measured E(θi)/ρ.
    let mut raw = vec![vec![Vec::new(); nt]; nr];
    let mut albedo = vec![vec![0.0; nt]; nr];
    for (i, &ti) in TABLE_THETA.iter().enumerate() {
        let setup = Setup {
            reflectance: 1.0,
            wi: spherical_direction_f64(ti.to_radians(), 0.0),
            wo: wo.clone(),
            photons: per,
            seed: 0,
            bounces: Bounces::All,
            max_bounces: 10_000,
        };
        let per_realisation: Vec<_> = realisations
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let seed = seed ^ ((i * 7919 + k) as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15);
                measure_reflectances(s, &Setup { seed, ..setup.clone() }, &rhos)
            })
            .collect::<Result<_, _>>()?;
        for (r, rho) in rhos.iter().enumerate() {
            albedo[r][i] = pool(&per_realisation.iter().map(|m: &Vec<_>| m[r].albedo).collect::<Vec<_>>()).mean / rho;
            raw[r][i] = (0..wo.len())
                .map(|j| {
                    let p = pool(&per_realisation.iter().map(|m: &Vec<_>| m[r].f[j]).collect::<Vec<_>>());
                    (p.mean / rho, p.half_width / rho)
                })
                .collect();
        }
    }
    // Reciprocity: f(θi, θo, Δφ) = f(θo, θi, Δφ); average the two independent measurements.
    let (mut values, mut widths) = (Vec::new(), Vec::new());
    for table in &raw {
        for i in 0..nt {
            for o in 0..nt {
                for p in 0..np {
                    let (a, b) = (table[i][o * np + p], table[o][i * np + p]);
                    let (v, h) = if i == o { a } else { (0.5 * (a.0 + b.0), 0.5 * a.1.hypot(b.1)) };
                    values.push(v as f32);
                    widths.push(h as f32);
                }
            }
        }
    }
    let relative: Vec<f64> =
        values.iter().zip(&widths).filter(|(v, _)| **v > 0.0).map(|(v, h)| (*h / *v) as f64).collect();
    let mut table = BrdfTable::new(
        description,
        TABLE_THETA.to_vec(),
        TABLE_DELTA_PHI.to_vec(),
        TABLE_REFLECTANCE.to_vec(),
        values,
        widths,
    )?;
    let albedo_before = table.max_albedo_over_reflectance();
    match_measured_albedo(&mut table, &albedo);
    let max_albedo = table.max_albedo_over_reflectance();
    let energy_scale = if max_albedo > 1.0 { 1.0 / max_albedo } else { 1.0 };
    table.scale(energy_scale as f32);
    let white_albedo = TABLE_THETA.iter().map(|&t| [t, table.albedo(t.to_radians().cos(), 1.0).value]).collect();
    Ok((
        table,
        TableReport {
            max_albedo_over_reflectance_before_matching: albedo_before,
            max_albedo_over_reflectance: max_albedo,
            energy_scale,
            mean_relative_half_width: relative.iter().sum::<f64>() / relative.len().max(1) as f64,
            max_relative_half_width: relative.iter().copied().fold(0.0, f64::max),
            white_albedo,
        },
    ))
}

/// Rescales the table symmetrically, f(θi, θo) ← sᵢ s_o f(θi, θo) per reflectance node, so that
/// the interpolated table's albedo on every θi node equals the albedo the escaping photons
/// measured there (an independent estimator; `docs/microgeometry.md#the-tabulated-ground-truth-brdf`).
/// Linear interpolation between 10° nodes misses the curvature of f toward grazing angles, and
/// this removes the resulting energy bias while keeping the table reciprocal. Fixed-point
/// iteration sᵢ ← sᵢ √(target/E) (a symmetric matrix-balancing step).
fn match_measured_albedo(table: &mut BrdfTable, target: &[Vec<f64>]) {
    let (nt, np) = (table.theta_deg.len(), table.delta_phi_deg.len());
    for (r, target) in target.iter().enumerate() {
        let rho = table.reflectance[r].max(1e-3) as f32;
        let base = r * nt * nt * np;
        for _ in 0..12 {
            let s: Vec<f64> = (0..nt)
                .map(|i| {
                    let e = table.albedo(table.theta_deg[i].to_radians().cos(), rho).value / rho as f64;
                    if e > 0.0 && target[i] > 0.0 { (target[i] / e).sqrt() } else { 1.0 }
                })
                .collect();
            for i in 0..nt {
                for o in 0..nt {
                    for p in 0..np {
                        let k = base + (i * nt + o) * np + p;
                        let f = (s[i] * s[o]) as f32;
                        table.f_over_reflectance[k] *= f;
                        if !table.half_width_over_reflectance.is_empty() {
                            table.half_width_over_reflectance[k] *= f;
                        }
                    }
                }
            }
        }
    }
}
