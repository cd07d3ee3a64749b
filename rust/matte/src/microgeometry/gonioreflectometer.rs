//! The virtual gonioreflectometer (`docs/microgeometry.md#the-estimator`): a distant source
//! along `wi` with unit irradiance on the beam, photons entering the macro plane uniformly,
//! Lambertian facets of albedo ρ, and a distant sensor in each direction `wo`.
//!
//! At every facet a photon reaches, the facet's radiance toward `wo` is added if the ray from
//! there along `wo` escapes (next-event estimation toward the sensor):
//!
//! ```text
//! f(wi, wo) = E[ Σ_hits  w · (ρ/π) · max(0, n·wo) · V(x, wo) ] / cos θo
//! ```
//!
//! where w is the photon's throughput before the hit (ρ^k after k bounces). For a flat surface
//! this is ρ/π exactly. Each photon's sum is one i.i.d. sample, so the 99 % interval comes from
//! their variance. The directional albedo is measured independently, as the mean throughput of
//! the photons that escape.

use super::estimate::{Estimate, RunningMean};
use super::surface::MicroSurface;
use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;
use std::f64::consts::{FRAC_1_PI, PI};

/// Which light paths are counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Bounces {
    /// Every bounce inside the microgeometry (the surface's true BRDF).
    All,
    /// Only light scattered once (shadowing and masking, no interreflection).
    First,
}

#[derive(Clone, Debug)]
pub struct Setup {
    /// Facet albedo ρ in [0, 1].
    pub reflectance: f64,
    /// Direction toward the source (unit, z > 0).
    pub wi: DVec3,
    /// Directions toward the sensor (unit, z > 0).
    pub wo: Vec<DVec3>,
    pub photons: u64,
    pub seed: u64,
    pub bounces: Bounces,
    /// Paths still inside after this many bounces are cut (their fraction is reported).
    pub max_bounces: u32,
}

#[derive(Clone, Debug)]
pub struct Measurement {
    /// f(wi, wo) per sensor direction.
    pub f: Vec<Estimate>,
    /// Directional albedo: the fraction of the incident power that leaves.
    pub albedo: Estimate,
    /// Fraction of photons cut at `max_bounces`.
    pub truncated: f64,
}

/// Photons per parallel work item (each with its own random stream).
const CHUNK: u64 = 1 << 14;

/// Measures `surface` under `setup`.
pub fn measure<S: MicroSurface>(surface: &S, setup: &Setup) -> Result<Measurement, String> {
    Ok(measure_reflectances(surface, setup, &[setup.reflectance])?.remove(0))
}

/// Measures `surface` under `setup` for several facet albedos at once (`setup.reflectance` is
/// not used): a path's geometry does not depend on ρ (no photon is absorbed; its throughput is
/// ρᵏ after k bounces), so each path is traced once and weighted for every ρ. One
/// [`Measurement`] per entry of `reflectances`.
pub fn measure_reflectances<S: MicroSurface>(
    surface: &S,
    setup: &Setup,
    reflectances: &[f64],
) -> Result<Vec<Measurement>, String> {
    if reflectances.is_empty() || reflectances.iter().any(|r| !(0.0..=1.0).contains(r)) {
        return Err(format!("reflectance must be in [0, 1], got {reflectances:?}"));
    }
    if !(setup.wi.z > 0.0) || setup.wo.iter().any(|w| !(w.z > 0.0)) {
        return Err("wi and every wo must point above the surface (z > 0)".into());
    }
    let chunks = setup.photons.div_ceil(CHUNK);
    let partial: Vec<(Vec<Vec<RunningMean>>, Vec<RunningMean>, u64)> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let n = CHUNK.min(setup.photons - c * CHUNK);
            let mut rng = Pcg64Mcg::seed_from_u64(setup.seed ^ (c + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15));
            trace_photons(surface, setup, reflectances, n, &mut rng)
        })
        .collect();
    let truncated = partial.iter().map(|p| p.2).sum::<u64>() as f64 / setup.photons.max(1) as f64;
    Ok((0..reflectances.len())
        .map(|r| {
            let mut f = vec![RunningMean::default(); setup.wo.len()];
            let mut albedo = RunningMean::default();
            for (pf, pa, _) in &partial {
                f.iter_mut().zip(&pf[r]).for_each(|(a, b)| a.merge(b));
                albedo.merge(&pa[r]);
            }
            Measurement { f: f.iter().map(RunningMean::estimate).collect(), albedo: albedo.estimate(), truncated }
        })
        .collect())
}

fn trace_photons<S: MicroSurface>(
    surface: &S,
    setup: &Setup,
    reflectances: &[f64],
    photons: u64,
    rng: &mut impl Rng,
) -> (Vec<Vec<RunningMean>>, Vec<RunningMean>, u64) {
    let nr = reflectances.len();
    let nw = setup.wo.len();
    let mut f = vec![vec![RunningMean::default(); nw]; nr];
    let mut albedo = vec![RunningMean::default(); nr];
    let mut truncated = 0;
    // Per-photon sums, reflectance-major.
    let mut sum = vec![0.0; nr * nw];
    let mut weight = vec![0.0; nr];
    let mut escaped = vec![0.0; nr];
    for _ in 0..photons {
        sum.iter_mut().for_each(|x| *x = 0.0);
        weight.iter_mut().for_each(|w| *w = 1.0);
        escaped.iter_mut().for_each(|e| *e = 0.0);
        let patch = surface.sample_patch(rng);
        let mut direction = -setup.wi;
        let mut origin = surface.entry_point(&patch, direction, rng);
        let mut bounce = 0;
        loop {
            let Some(hit) = surface.intersect(&patch, origin, direction) else {
                if bounce > 0 {
                    escaped.copy_from_slice(&weight);
                }
                break;
            };
            if bounce == setup.max_bounces {
                truncated += 1;
                break;
            }
            for (j, wo) in setup.wo.iter().enumerate() {
                let c = hit.normal.dot(*wo);
                if c > 0.0 && surface.intersect(&patch, hit.point, *wo).is_none() {
                    let geometry = FRAC_1_PI * c / wo.z;
                    for (r, rho) in reflectances.iter().enumerate() {
                        sum[r * nw + j] += weight[r] * rho * geometry;
                    }
                }
            }
            weight.iter_mut().zip(reflectances).for_each(|(w, rho)| *w *= rho);
            bounce += 1;
            direction = cosine_around(hit.normal, rng);
            origin = hit.point;
            if setup.bounces == Bounces::First {
                let out = surface.intersect(&patch, origin, direction).is_none();
                escaped.iter_mut().zip(&weight).for_each(|(e, w)| *e = if out { *w } else { 0.0 });
                break;
            }
        }
        for r in 0..nr {
            f[r].iter_mut().zip(&sum[r * nw..(r + 1) * nw]).for_each(|(m, x)| m.push(*x));
            albedo[r].push(escaped[r]);
        }
    }
    (f, albedo, truncated)
}

/// A cosine-distributed direction about the unit normal `n`.
fn cosine_around(n: DVec3, rng: &mut impl Rng) -> DVec3 {
    let (u1, u2): (f64, f64) = (rng.random(), rng.random());
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    let (t, b) = n.any_orthonormal_pair();
    (t * (r * phi.cos()) + b * (r * phi.sin()) + n * (1.0 - u1).max(0.0).sqrt()).normalize()
}
