//! `matte microgeometry`: simulate a rough model's own microsurface and compare the analytic
//! models with it (`docs/microgeometry.md`). Prints the comparison as JSON.

use crate::microgeometry::comparison::{compare_height_field, compare_v_cavities};
use crate::microgeometry::tabulation::tabulate;
use crate::microgeometry::{HeightField, VCavities};
use clap::{Args, ValueEnum};

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum SurfaceKind {
    /// Oren–Nayar's V-cavities (against Oren–Nayar and EON).
    VCavities,
    /// A Gaussian random height field (against van Ginneken).
    HeightField,
}

#[derive(Args, Debug)]
pub struct MicrogeometryArgs {
    #[arg(long, value_enum, default_value_t = SurfaceKind::VCavities)]
    pub surface: SurfaceKind,
    /// σ of the V-cavities (slope-angle standard deviation, radians) or m of the height field
    /// (per-axis rms slope).
    #[arg(long, default_value_t = 0.3)]
    pub roughness: f64,
    /// Height field: grid cells per side (8 per correlation length).
    #[arg(long, default_value_t = 256)]
    pub cells: usize,
    /// Height field: independent realisations pooled (photons are split between them; the
    /// interval comes from their spread).
    #[arg(long, default_value_t = 8)]
    pub realisations: usize,
    /// Facet albedo ρ.
    #[arg(long, default_value_t = 0.8)]
    pub reflectance: f64,
    /// Photons per incidence angle (and per bounce setting).
    #[arg(long, default_value_t = 1_000_000)]
    pub photons: u64,
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Instead of the comparison, tabulate the surface's BRDF into this file (the tabulated
    /// BSDF's JSON format, `docs/microgeometry.md#file-format`); `--photons` is then per θi node
    /// and `--reflectance` is not used (the table covers ρ ∈ [0, 1]).
    #[arg(long)]
    pub table: Option<std::path::PathBuf>,
}

pub fn run(a: &MicrogeometryArgs) -> Result<(), String> {
    if !(0.0..=1.0).contains(&a.reflectance) {
        return Err(format!("--reflectance must lie in [0, 1] (got {})", a.reflectance));
    }
    if a.photons < 2 {
        return Err(format!("--photons must be at least 2 (got {})", a.photons));
    }
    if let Some(path) = &a.table {
        return write_table(a, path);
    }
    let c = match a.surface {
        SurfaceKind::VCavities => compare_v_cavities(a.roughness, a.reflectance, a.photons, a.seed)?,
        SurfaceKind::HeightField => {
            compare_height_field(a.roughness, a.cells, a.realisations, a.reflectance, a.photons, a.seed)?
        }
    };
    println!("{}", serde_json::to_string_pretty(&c).map_err(|e| format!("JSON output: {e}"))?);
    Ok(())
}

fn write_table(a: &MicrogeometryArgs, path: &std::path::Path) -> Result<(), String> {
    let (table, report) = match a.surface {
        SurfaceKind::VCavities => {
            let what = format!("V-cavities, sigma = {} rad, {} photons per theta_i", a.roughness, a.photons);
            tabulate(&[VCavities::new(a.roughness)?], &what, a.photons, a.seed)?
        }
        SurfaceKind::HeightField => {
            if a.realisations == 0 {
                return Err("--realisations must be at least 1".into());
            }
            let surfaces: Vec<HeightField> = (0..a.realisations as u64)
                .map(|k| HeightField::gaussian(a.roughness, a.cells, a.seed.wrapping_add(k)))
                .collect::<Result<_, _>>()?;
            let what = format!(
                "Gaussian height field, m = {}, {} realisations of {} T, {} photons per theta_i",
                a.roughness,
                a.realisations,
                a.cells / 8,
                a.photons
            );
            tabulate(&surfaces, &what, a.photons, a.seed)?
        }
    };
    table.write(path)?;
    println!("{}", serde_json::to_string_pretty(&report).map_err(|e| format!("JSON output: {e}"))?);
    Ok(())
}
