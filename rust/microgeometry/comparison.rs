//! Each analytic model against a simulation of the surface it describes
//! (`docs/microgeometry.md#comparison`): the surface's BRDF measured on a (θi, θo, Δφ) grid
//! with all bounces and with the first only, beside the kernels' values, and the directional
//! albedo per θi. V-cavities face the Oren–Nayar family, Gaussian height fields van Ginneken.

use super::estimate::Estimate;
use super::gonioreflectometer::{Bounces, Setup, measure};
use super::height_field::HeightField;
use super::surface::MicroSurface;
use super::v_cavity::VCavities;
use crate::brdf::frame::spherical_direction_f64;
use crate::brdf::oren_nayar::OrenNayarKernel;
use crate::brdf::{DiffuseBrdf, DiffuseModel, OrenNayarModel, ParamValue, Params};
use glam::DVec3;
use serde::Serialize;

/// Incidence angles of the grid (degrees).
pub const THETA_I: [f64; 4] = [0.0, 30.0, 60.0, 75.0];
/// Outgoing zenith angles (degrees).
pub const THETA_O: [f64; 9] = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0];
/// Azimuth differences: forward (0° is the same side as the source, backscatter), cross-plane
/// and specular side (degrees).
pub const DELTA_PHI: [f64; 3] = [0.0, 90.0, 180.0];

#[derive(Serialize)]
pub struct Comparison {
    /// "v_cavities" or "gaussian_height_field".
    pub surface: &'static str,
    /// σ (V-cavities, radians) or m (height field, per-axis rms slope).
    pub roughness: f64,
    pub reflectance: f64,
    pub photons: u64,
    pub models: Vec<String>,
    pub points: Vec<GridPoint>,
    pub albedo: Vec<AlbedoPoint>,
    pub summary: Vec<ModelError>,
}

#[derive(Serialize)]
pub struct GridPoint {
    pub theta_i: f64,
    pub theta_o: f64,
    pub delta_phi: f64,
    /// The surface's BRDF, all bounces.
    pub simulated: Estimate,
    /// First bounce only.
    pub single_bounce: Estimate,
    /// Each model's f, in the order of `models`.
    pub model: Vec<f64>,
}

#[derive(Serialize)]
pub struct AlbedoPoint {
    pub theta_i: f64,
    pub simulated: Estimate,
    pub single_bounce: Estimate,
    pub model: Vec<f64>,
}

/// One model's relative error against the all-bounce simulation over the grid.
#[derive(Serialize)]
pub struct ModelError {
    pub model: String,
    pub mean_abs_relative_error: f64,
    pub max_abs_relative_error: f64,
    /// (θi, θo, Δφ) of the largest error.
    pub worst_at: [f64; 3],
    pub max_abs_albedo_relative_error: f64,
}

fn build(kind: &str, params: &[(&str, ParamValue)]) -> Result<DiffuseModel, String> {
    let mut p = Params::new();
    params.iter().for_each(|(n, v)| p.push(n, v.clone()));
    DiffuseModel::from_params(kind, p).map_err(|e| e.to_string())
}

fn direction(theta_deg: f64, phi_deg: f64) -> DVec3 {
    spherical_direction_f64(theta_deg.to_radians(), phi_deg.to_radians())
}

/// The kernels compared with V-cavities of slope deviation `sigma`: Oren–Nayar qualitative and
/// full at σ, and EON at r = B/A of the qualitative model (its ratio of the two terms).
pub fn v_cavity_models(sigma: f64) -> Result<Vec<(String, DiffuseModel)>, String> {
    let qualitative = OrenNayarKernel::<f64>::new(sigma, OrenNayarModel::Qualitative);
    let r = (qualitative.b / qualitative.a).min(1.0);
    use ParamValue::{Number as N, Text as T};
    Ok(vec![
        ("Oren–Nayar qualitative".into(), build("oren_nayar", &[("sigma", N(sigma))])?),
        ("Oren–Nayar full".into(), build("oren_nayar", &[("sigma", N(sigma)), ("model", T("full".into()))])?),
        (format!("EON (r = {r:.3})"), build("eon", &[("roughness", N(r))])?),
    ])
}

/// The kernels compared with a Gaussian height field of per-axis rms slope `m`: van Ginneken
/// with both shadowing options.
pub fn height_field_models(m: f64) -> Result<Vec<(String, DiffuseModel)>, String> {
    use ParamValue::{Number as N, Text as T};
    Ok(vec![
        ("van Ginneken (vginneken)".into(), build("ginneken", &[("roughness", N(m))])?),
        (
            "van Ginneken (height_correlated)".into(),
            build("ginneken", &[("roughness", N(m)), ("shadowing", T("height_correlated".into()))])?,
        ),
    ])
}

/// V-cavities of slope deviation `sigma` against the Oren–Nayar family.
pub fn compare_v_cavities(sigma: f64, reflectance: f64, photons: u64, seed: u64) -> Result<Comparison, String> {
    let surface = VCavities::new(sigma)?;
    compare(&surface, "v_cavities", sigma, v_cavity_models(sigma)?, reflectance, photons, seed)
}

/// One `cells`² realisation of the Gaussian height field with rms slope `m` against van
/// Ginneken.
pub fn compare_height_field(
    m: f64,
    cells: usize,
    reflectance: f64,
    photons: u64,
    seed: u64,
) -> Result<Comparison, String> {
    if m == 0.0 {
        return Err("van Ginneken needs a roughness above 0".into());
    }
    let surface = HeightField::gaussian(m, cells, seed)?;
    compare(&surface, "gaussian_height_field", m, height_field_models(m)?, reflectance, photons, seed)
}

fn compare<S: MicroSurface>(
    surface: &S,
    name: &'static str,
    roughness: f64,
    models: Vec<(String, DiffuseModel)>,
    reflectance: f64,
    photons: u64,
    seed: u64,
) -> Result<Comparison, String> {
    let rho = [reflectance as f32];
    let wo: Vec<DVec3> = THETA_O.iter().flat_map(|&t| DELTA_PHI.map(|p| direction(t, p))).collect();
    let mut points = Vec::new();
    let mut albedo = Vec::new();
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
        let all = measure(surface, &setup(Bounces::All))?;
        let first = measure(surface, &setup(Bounces::First))?;
        for (j, w) in wo.iter().enumerate() {
            points.push(GridPoint {
                theta_i: ti,
                theta_o: THETA_O[j / DELTA_PHI.len()],
                delta_phi: DELTA_PHI[j % DELTA_PHI.len()],
                simulated: all.f[j],
                single_bounce: first.f[j],
                model: models.iter().map(|(_, m)| m.eval(wi.as_vec3(), w.as_vec3(), rho)[0] as f64).collect(),
            });
        }
        albedo.push(AlbedoPoint {
            theta_i: ti,
            simulated: all.albedo,
            single_bounce: first.albedo,
            model: models.iter().map(|(_, m)| m.albedo(wi.z, rho[0]).value).collect(),
        });
    }
    let summary = models
        .iter()
        .enumerate()
        .map(|(m, (label, _))| {
            let errors: Vec<(f64, [f64; 3])> = points
                .iter()
                .map(|p| ((p.model[m] / p.simulated.mean - 1.0).abs(), [p.theta_i, p.theta_o, p.delta_phi]))
                .collect();
            let worst = errors.iter().copied().max_by(|a, b| a.0.total_cmp(&b.0)).unwrap_or((f64::NAN, [0.0; 3]));
            ModelError {
                model: label.clone(),
                mean_abs_relative_error: errors.iter().map(|e| e.0).sum::<f64>() / errors.len() as f64,
                max_abs_relative_error: worst.0,
                worst_at: worst.1,
                max_abs_albedo_relative_error: albedo
                    .iter()
                    .map(|a| (a.model[m] / a.simulated.mean - 1.0).abs())
                    .fold(0.0, f64::max),
            }
        })
        .collect();
    Ok(Comparison {
        surface: name,
        roughness,
        reflectance,
        photons,
        models: models.into_iter().map(|(l, _)| l).collect(),
        points,
        albedo,
        summary,
    })
}
