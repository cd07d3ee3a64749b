//! Each analytic model against a simulation of the surface it describes
//! (`docs/microgeometry.md#comparison`): the surface's BRDF measured on a (θi, θo, Δφ) grid
//! with all bounces and with the first only, beside the kernels' values, and the directional
//! albedo per θi. Every model faces both surfaces (V-cavities and Gaussian height fields), so
//! each can be judged on its own surface and on the other.

use super::gonioreflectometer::{Bounces, Measurement, Setup, measure};
use super::height_field::HeightField;
use super::realisations::{PooledEstimate, pool};
use super::v_cavity::VCavities;
use glam::DVec3;
use matte_brdf::frame::spherical_direction_f64;
use matte_brdf::oren_nayar::OrenNayarCoefficients;
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue};
use serde::Serialize;

/// Incidence angles of the grid (degrees).
pub const THETA_I: [f64; 4] = [0.0, 30.0, 60.0, 75.0];
/// Outgoing zenith angles (degrees).
pub const THETA_O: [f64; 9] = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0];
/// Azimuth differences: forward (0° is the same side as the source, backscatter), cross-plane
/// and specular side (degrees).
pub const DELTA_PHI: [f64; 3] = [0.0, 90.0, 180.0];

#[derive(Serialize)]
pub struct ModelComparison {
    /// "v_cavities" or "gaussian_height_field".
    pub surface: &'static str,
    /// σ (V-cavities, radians) or m (height field, per-axis rms slope).
    pub roughness: f64,
    pub reflectance: f64,
    /// Photons per incidence angle and bounce setting (all realisations together).
    pub photons: u64,
    /// Height field: cells per side of one realisation (8 per correlation length T); 0 for
    /// V-cavities.
    pub cells: usize,
    /// Independent surface realisations pooled (1 for V-cavities: every photon draws its own
    /// cavity).
    pub realisations: usize,
    pub models: Vec<String>,
    pub points: Vec<GridPoint>,
    pub albedo: Vec<AlbedoPoint>,
    /// Each model against the all-bounce simulation.
    pub summary: Vec<ModelDeviation>,
    /// Each model against the first-bounce simulation (no interreflection).
    pub summary_single_bounce: Vec<ModelDeviation>,
}

#[derive(Serialize)]
pub struct GridPoint {
    pub theta_i: f64,
    pub theta_o: f64,
    pub delta_phi: f64,
    /// The surface's BRDF, all bounces.
    pub simulated: PooledEstimate,
    /// First bounce only.
    pub single_bounce: PooledEstimate,
    /// Each model's f, in the order of `models`.
    pub model: Vec<f64>,
}

#[derive(Serialize)]
pub struct AlbedoPoint {
    pub theta_i: f64,
    pub simulated: PooledEstimate,
    pub single_bounce: PooledEstimate,
    pub model: Vec<f64>,
}

/// One model's relative error against one simulation over the grid.
#[derive(Serialize)]
pub struct ModelDeviation {
    pub model: String,
    pub mean_abs_relative_error: f64,
    pub max_abs_relative_error: f64,
    /// (θi, θo, Δφ) of the largest error.
    pub worst_at: [f64; 3],
    pub max_abs_albedo_relative_error: f64,
    /// θi of the largest albedo error.
    pub worst_albedo_at: f64,
}

fn direction(theta_deg: f64, phi_deg: f64) -> DVec3 {
    spherical_direction_f64(theta_deg.to_radians(), phi_deg.to_radians())
}

/// EON's roughness r at Oren–Nayar's σ by the ratio of the qualitative model's two terms,
/// r = B/A (FON's B_F/A_F is r): the mapping before any measurement.
pub fn eon_roughness_by_term_ratio(sigma: f64) -> f64 {
    let c = OrenNayarCoefficients::<f64>::new(sigma);
    (c.b / c.a).min(1.0)
}

/// Every model named in `docs/microgeometry.md#comparison` at one roughness s: Oren–Nayar
/// qualitative and full at σ = s, EON at r = B/A (of the qualitative model at σ = s) and van
/// Ginneken at m = s with both shadowing options (σ = m is Mitsuba 0.6's `roughdiffuse`
/// conversion σ = α/√2 with α = √2 m; `docs/models.md`). van Ginneken needs s > 0.
pub fn models_at(s: f64) -> Result<Vec<(String, DiffuseModel)>, String> {
    use ParamValue::{Number as N, Text as T};
    let r = eon_roughness_by_term_ratio(s);
    let mut models = vec![
        ("Oren–Nayar qualitative".into(), DiffuseModel::with("oren_nayar", &[("sigma", N(s))])?),
        ("Oren–Nayar full".into(), DiffuseModel::with("oren_nayar", &[("sigma", N(s)), ("model", T("full".into()))])?),
        (format!("EON (r = B/A = {r:.3})"), DiffuseModel::with("eon", &[("roughness", N(r))])?),
    ];
    if s > 0.0 {
        models.push(("van Ginneken (vginneken)".into(), DiffuseModel::with("ginneken", &[("roughness", N(s))])?));
        models.push((
            "van Ginneken (height_correlated)".into(),
            DiffuseModel::with("ginneken", &[("roughness", N(s)), ("shadowing", T("height_correlated".into()))])?,
        ));
    }
    Ok(models)
}

/// V-cavities of slope deviation `sigma` against every model, plus EON at the r that fits them
/// best.
pub fn compare_v_cavities(sigma: f64, reflectance: f64, photons: u64, seed: u64) -> Result<ModelComparison, String> {
    let surface = VCavities::new(sigma)?;
    let run = |setup: &Setup| Ok(vec![measure(&surface, setup)?]);
    compare("v_cavities", sigma, 0, 1, models_at(sigma)?, reflectance, photons, seed, run)
}

/// `realisations` independent `cells`² realisations of the Gaussian height field with rms slope
/// `m` against every model, photons split equally between them.
pub fn compare_height_field(
    m: f64,
    cells: usize,
    realisations: usize,
    reflectance: f64,
    photons: u64,
    seed: u64,
) -> Result<ModelComparison, String> {
    if m == 0.0 {
        return Err("van Ginneken needs a roughness above 0".into());
    }
    if realisations == 0 {
        return Err("at least one height-field realisation is needed".into());
    }
    let per = photons / realisations as u64;
    if per < 2 {
        return Err(format!("{photons} photons cannot be split over {realisations} realisations"));
    }
    let surfaces: Vec<HeightField> = (0..realisations)
        .map(|k| HeightField::gaussian(m, cells, realisation_seed(seed, k)))
        .collect::<Result<_, _>>()?;
    let run = |setup: &Setup| {
        surfaces
            .iter()
            .enumerate()
            .map(|(k, s)| measure(s, &Setup { photons: per, seed: realisation_seed(setup.seed, k), ..setup.clone() }))
            .collect()
    };
    compare(
        "gaussian_height_field",
        m,
        cells,
        realisations,
        models_at(m)?,
        reflectance,
        per * realisations as u64,
        seed,
        run,
    )
}

/// Seed of realisation k (k = 0 keeps `seed`, so one realisation is the old single patch).
fn realisation_seed(seed: u64, k: usize) -> u64 {
    seed ^ (k as u64).wrapping_mul(0xd1b5_4a32_d192_ed03)
}

#[allow(clippy::too_many_arguments)]
fn compare(
    name: &'static str,
    roughness: f64,
    cells: usize,
    realisations: usize,
    mut models: Vec<(String, DiffuseModel)>,
    reflectance: f64,
    photons: u64,
    seed: u64,
    run: impl Fn(&Setup) -> Result<Vec<Measurement>, String>,
) -> Result<ModelComparison, String> {
    let wo: Vec<DVec3> = THETA_O.iter().flat_map(|&t| DELTA_PHI.map(|p| direction(t, p))).collect();
    let mut sims = Vec::new();
    for (k, &ti) in THETA_I.iter().enumerate() {
        let wi = direction(ti, 0.0);
        let setup = |bounces| Setup {
            reflectance,
            wi,
            wo: wo.clone(),
            photons,
            seed: seed + 1000 * k as u64 + (bounces == Bounces::First) as u64,
            bounces,
            max_bounces: 1000,
        };
        let all = run(&setup(Bounces::All))?;
        let first = run(&setup(Bounces::First))?;
        let column = |ms: &[Measurement], j: usize| pool(&ms.iter().map(|m| m.f[j]).collect::<Vec<_>>());
        let f: Vec<_> = (0..wo.len()).map(|j| (column(&all, j), column(&first, j))).collect();
        let albedo = (
            pool(&all.iter().map(|m| m.albedo).collect::<Vec<_>>()),
            pool(&first.iter().map(|m| m.albedo).collect::<Vec<_>>()),
        );
        sims.push((ti, wi, f, albedo));
    }
    // EON at the r that fits this surface best (all bounces).
    let targets: Vec<(DVec3, DVec3, f64)> =
        sims.iter().flat_map(|(_, wi, f, _)| f.iter().zip(&wo).map(|((all, _), w)| (*wi, *w, all.mean))).collect();
    let r = super::eon_fit::best_eon_roughness(&targets, reflectance)?;
    models.push((
        format!("EON (fitted r = {r:.3})"),
        DiffuseModel::with("eon", &[("roughness", ParamValue::Number(r))])?,
    ));

    let rho = [reflectance as f32];
    let mut points = Vec::new();
    let mut albedo = Vec::new();
    for (ti, wi, f, (all, first)) in &sims {
        for (j, w) in wo.iter().enumerate() {
            points.push(GridPoint {
                theta_i: *ti,
                theta_o: THETA_O[j / DELTA_PHI.len()],
                delta_phi: DELTA_PHI[j % DELTA_PHI.len()],
                simulated: f[j].0,
                single_bounce: f[j].1,
                model: models.iter().map(|(_, m)| m.eval(wi.as_vec3(), w.as_vec3(), rho)[0] as f64).collect(),
            });
        }
        albedo.push(AlbedoPoint {
            theta_i: *ti,
            simulated: *all,
            single_bounce: *first,
            model: models.iter().map(|(_, m)| m.albedo(wi.z, rho[0]).value).collect(),
        });
    }
    let labels: Vec<String> = models.into_iter().map(|(l, _)| l).collect();
    Ok(ModelComparison {
        surface: name,
        roughness,
        reflectance,
        photons,
        cells,
        realisations,
        summary: errors(&labels, &points, &albedo, |p| p.simulated.mean, |a| a.simulated.mean),
        summary_single_bounce: errors(&labels, &points, &albedo, |p| p.single_bounce.mean, |a| a.single_bounce.mean),
        models: labels,
        points,
        albedo,
    })
}

/// Each model's relative errors against the simulated values `sim` and `sim_albedo` select.
fn errors(
    labels: &[String],
    points: &[GridPoint],
    albedo: &[AlbedoPoint],
    sim: impl Fn(&GridPoint) -> f64,
    sim_albedo: impl Fn(&AlbedoPoint) -> f64,
) -> Vec<ModelDeviation> {
    labels
        .iter()
        .enumerate()
        .map(|(m, label)| {
            let errors: Vec<(f64, [f64; 3])> = points
                .iter()
                .map(|p| ((p.model[m] / sim(p) - 1.0).abs(), [p.theta_i, p.theta_o, p.delta_phi]))
                .collect();
            let worst = errors.iter().copied().max_by(|a, b| a.0.total_cmp(&b.0)).unwrap_or((f64::NAN, [0.0; 3]));
            let worst_albedo = albedo
                .iter()
                .map(|a| ((a.model[m] / sim_albedo(a) - 1.0).abs(), a.theta_i))
                .max_by(|a, b| a.0.total_cmp(&b.0))
                .unwrap_or((f64::NAN, 0.0));
            ModelDeviation {
                model: label.clone(),
                mean_abs_relative_error: errors.iter().map(|e| e.0).sum::<f64>() / errors.len() as f64,
                max_abs_relative_error: worst.0,
                worst_at: worst.1,
                max_abs_albedo_relative_error: worst_albedo.0,
                worst_albedo_at: worst_albedo.1,
            }
        })
        .collect()
}
