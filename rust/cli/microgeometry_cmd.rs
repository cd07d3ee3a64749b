//! `matte microgeometry`: simulate a rough model's own microsurface and compare the analytic
//! models with it (`docs/microgeometry.md`). Prints the comparison as JSON.

use crate::microgeometry::comparison::compare_v_cavities;
use clap::Args;

#[derive(Args, Debug)]
pub struct MicrogeometryArgs {
    /// Slope-angle standard deviation σ of the V-cavities (radians).
    #[arg(long, default_value_t = 0.3)]
    pub sigma: f64,
    /// Facet albedo ρ.
    #[arg(long, default_value_t = 0.8)]
    pub reflectance: f64,
    /// Photons per incidence angle (and per bounce setting).
    #[arg(long, default_value_t = 1_000_000)]
    pub photons: u64,
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

pub fn run(a: &MicrogeometryArgs) -> Result<(), String> {
    if !(0.0..=1.0).contains(&a.reflectance) {
        return Err(format!("--reflectance must lie in [0, 1] (got {})", a.reflectance));
    }
    if a.photons < 2 {
        return Err(format!("--photons must be at least 2 (got {})", a.photons));
    }
    let c = compare_v_cavities(a.sigma, a.reflectance, a.photons, a.seed)?;
    println!("{}", serde_json::to_string_pretty(&c).map_err(|e| format!("JSON output: {e}"))?);
    Ok(())
}
