//! `summary.json`, the machine-readable verdict of `matte validate` (also printed with
//! `--json`): one typed record per scene × reference, serialised with serde. Field names are
//! the file's format; `docs/validation.md` explains what each test measures.

use super::SceneResult;
use super::crop::PixelBox;
use super::power::{Calibration, PowerCurve, Rate};
use super::scales::Rejection;
use glam::DVec3;
use serde::Serialize;
use std::path::Path;

#[derive(Serialize)]
pub struct Summary<'a> {
    pub passed: bool,
    /// What was compared with what: matte's and Mitsuba's versions, the variants, where the
    /// scenes came from.
    pub provenance: &'a Provenance,
    pub scenes: Vec<SceneSummary<'a>>,
}

/// What a validation run compared: matte's version, the Mitsuba it ran (version, variants,
/// the Python environment) and where the scenes came from. In the summary and the report.
#[derive(Clone, Debug, Serialize)]
pub struct Provenance {
    /// matte's version.
    pub matte: String,
    /// The installed Mitsuba's version (`None`: only the Rust renderer ran, `--self-check`).
    pub mitsuba: Option<String>,
    /// The references: `mitsuba llvm_ad_rgb`, …, or `matte` for `--self-check`.
    pub references: Vec<String>,
    /// The Python side that ran Mitsuba (interpreter, how it was chosen, package folder).
    pub python: Option<String>,
    /// Where the scenes came from (the bundled ones with their folder, or the command line).
    pub scenes: String,
}

#[derive(Serialize)]
pub struct SceneSummary<'a> {
    scene: String,
    reference: &'a str,
    passed: bool,
    width: u32,
    height: u32,
    passes: u32,
    spp_per_pass: u32,
    alpha: f64,
    alpha_pixel: f64,
    rejected_pixels: usize,
    rejected_fraction: f64,
    uncorrected_rejection_rate: f64,
    scales: Vec<ScaleSummary>,
    power: Option<PowerSummary>,
    predicted_power: PredictedSummary,
    global: GlobalSummary,
    seconds_matte: f64,
    seconds_reference: f64,
    files: FileSummary<'a>,
}

#[derive(Serialize)]
struct ScaleSummary {
    scale: String,
    blocks: usize,
    alpha_test: f64,
    rejected: usize,
    min_p: f64,
    worst: Vec<RejectionSummary>,
}

#[derive(Serialize)]
struct RejectionSummary {
    scale: String,
    place: Place,
    p: f64,
    t: [f64; 3],
    rel_diff: f64,
}

/// A pixel box `[x0, x1) × [y0, y1)`.
#[derive(Serialize)]
struct Place {
    x0: u32,
    y0: u32,
    x1: u32,
    y1: u32,
}

#[derive(Serialize)]
struct PowerSummary {
    replicates: usize,
    unchanged: RateSummary,
    identical_matte: RateSummary,
    identical_reference: RateSummary,
    uniform: CurveSummary,
    patch: CurveSummary,
    patch_place: Place,
}

/// What the run's own variances predict (a lower bound on power; `validate::predicted_power`).
#[derive(Serialize)]
struct PredictedSummary {
    /// Smallest uniform relative change detected with 80 % power (`null`: none up to 10⁶).
    uniform_80: Option<f64>,
    /// The same for a change confined to `patch_place`.
    patch_80: Option<f64>,
    patch_place: Place,
}

#[derive(Serialize)]
struct RateSummary {
    rejected: usize,
    pairs: usize,
    /// `(scale, pairs rejected at it)`.
    by_scale: Vec<(String, usize)>,
}

#[derive(Serialize)]
struct CurveSummary {
    /// Smallest injected relative change detected with 80 % power.
    detected_80: Option<f64>,
    /// `(δ, power)` pairs.
    curve: Vec<(f64, f64)>,
}

#[derive(Serialize)]
struct GlobalSummary {
    mean_matte: [f64; 3],
    mean_reference: [f64; 3],
    difference: [f64; 3],
    ci99_half_width: [f64; 3],
    p: [f64; 3],
    rejected: bool,
}

#[derive(Serialize)]
struct FileSummary<'a> {
    matte_exr: &'a Path,
    matte_png: &'a Path,
    reference_exr: &'a Path,
    reference_png: &'a Path,
    difference_png: &'a Path,
    pvalues_png: &'a Path,
    difference_range: f32,
}

fn place(b: &PixelBox) -> Place {
    Place { x0: b.x0, y0: b.y0, x1: b.x1, y1: b.y1 }
}

fn rejection(r: &Rejection) -> RejectionSummary {
    RejectionSummary { scale: r.scale.key(), place: place(&r.place), p: r.p, t: r.t.to_array(), rel_diff: r.rel_diff }
}

fn rate(r: &Rate) -> RateSummary {
    RateSummary { rejected: r.rejected, pairs: r.pairs, by_scale: r.by_scale.clone() }
}

fn curve(c: &PowerCurve) -> CurveSummary {
    CurveSummary { detected_80: c.detected, curve: c.curve.clone() }
}

fn power(p: &Calibration) -> PowerSummary {
    PowerSummary {
        replicates: p.replicates,
        unchanged: rate(&p.unchanged),
        identical_matte: rate(&p.identical_matte),
        identical_reference: rate(&p.identical_reference),
        uniform: curve(&p.uniform),
        patch: curve(&p.patch),
        patch_place: place(&p.patch_place),
    }
}

fn array(v: DVec3) -> [f64; 3] {
    v.to_array()
}

impl<'a> Summary<'a> {
    pub fn new(results: &'a [SceneResult], provenance: &'a Provenance) -> Summary<'a> {
        let scenes = results
            .iter()
            .map(|r| {
                let c = &r.comparison;
                SceneSummary {
                    scene: r.scene.display().to_string(),
                    reference: &r.reference,
                    passed: c.passed(),
                    width: c.width,
                    height: c.height,
                    passes: r.passes,
                    spp_per_pass: r.spp_per_pass,
                    alpha: c.alpha,
                    alpha_pixel: c.alpha_pixel,
                    rejected_pixels: c.rejected_pixels,
                    rejected_fraction: c.rejected_fraction(),
                    uncorrected_rejection_rate: c.uncorrected_rejection_rate,
                    scales: c
                        .scales
                        .iter()
                        .map(|s| ScaleSummary {
                            scale: s.scale.key(),
                            blocks: s.blocks,
                            alpha_test: s.alpha_test,
                            rejected: s.rejected,
                            min_p: s.min_p,
                            worst: s.worst.iter().map(rejection).collect(),
                        })
                        .collect(),
                    power: r.power.as_ref().map(power),
                    predicted_power: PredictedSummary {
                        uniform_80: r.predicted_power.uniform,
                        patch_80: r.predicted_power.patch,
                        patch_place: place(&r.predicted_power.patch_place),
                    },
                    global: GlobalSummary {
                        mean_matte: array(c.global.mean_a),
                        mean_reference: array(c.global.mean_b),
                        difference: array(c.global.diff),
                        ci99_half_width: array(c.global.ci99),
                        p: array(c.global.p),
                        rejected: c.global.rejected,
                    },
                    seconds_matte: r.seconds_matte,
                    seconds_reference: r.seconds_reference,
                    files: FileSummary {
                        matte_exr: &r.files.matte_exr,
                        matte_png: &r.files.matte_png,
                        reference_exr: &r.files.reference_exr,
                        reference_png: &r.files.reference_png,
                        difference_png: &r.files.difference_png,
                        pvalues_png: &r.files.pvalues_png,
                        difference_range: r.files.difference_range,
                    },
                }
            })
            .collect();
        Summary { passed: results.iter().all(|r| r.comparison.passed()), provenance, scenes }
    }

    /// The pretty-printed JSON text.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a summary of numbers and strings always serialises")
    }
}
