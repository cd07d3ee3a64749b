//! `matte validate`: renders scenes with the Rust renderer and with Mitsuba 3.9.1 (matte's
//! plugins loaded) in independent passes ([`passes`]) and decides with statistical tests at
//! several scales — pixels, blocks, the whole image ([`scales`], [`stats`]) — whether the two
//! expected images agree; `--power` measures what the budget detects ([`power`]); writes both
//! images, heatmaps ([`heatmap`]), crops of rejected places, `summary.json` and `report.html`
//! ([`validation_report`]). `docs/validation.md` has the method and the measured numbers.

pub mod crop;
pub mod heatmap;
pub mod passes;
pub mod power;
pub mod predicted_power;
pub mod scales;
pub mod stats;
pub mod summary;
pub mod validation_report;
pub mod welch;

use matte_render::film::SplatWeights;
use matte_render::image_io;
use passes::{Budget, PassPlan, Renderer, Side};
use std::path::{Path, PathBuf};

#[derive(Clone, Debug)]
pub struct ValidateOptions {
    pub passes: u32,
    /// Total samples per pixel per renderer (split over the passes); `None` = 4× the scene's
    /// `sample_count`.
    pub spp: Option<u32>,
    pub seed: u64,
    /// Family-wise level of all tests over all scales.
    pub alpha: f64,
    pub out: PathBuf,
    pub matte_defines: Vec<(String, String)>,
    pub reference_defines: Vec<(String, String)>,
    /// The Rust renderer renders this file instead of the scene (a modified scene, to
    /// measure what the test detects).
    pub matte_scene: Option<PathBuf>,
    /// `--power`: replicates of each side for the power calibration ([`power`]).
    pub power_replicates: Option<u32>,
}

/// One scene × reference.
#[derive(Clone, Debug)]
pub struct SceneResult {
    pub scene: PathBuf,
    pub name: String,
    pub reference: String,
    pub comparison: stats::ImageComparison,
    pub seconds_matte: f64,
    pub seconds_reference: f64,
    pub passes: u32,
    pub spp_per_pass: u32,
    /// `--power`: what this budget detects, measured by injection over replicates.
    pub power: Option<power::Calibration>,
    /// What this budget detects, predicted from this run's variances (a lower bound on power).
    pub predicted_power: predicted_power::Prediction,
    /// Files, relative to the output folder.
    pub files: validation_report::Files,
}

pub fn validate_scene(
    scene: &Path,
    reference: &Renderer,
    opts: &ValidateOptions,
    progress: &dyn Fn(&str, u32, u32),
) -> Result<SceneResult, String> {
    let name = scene.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scene".into());
    let ref_label = match reference {
        Renderer::Mitsuba(v) => v.clone(),
        Renderer::Matte => "matte".into(),
    };
    let rel_dir = PathBuf::from(&name).join(&ref_label);
    let dir = opts.out.join(&rel_dir);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let budget = match opts.spp {
        Some(total) => Budget::PerPass((total / opts.passes).max(1)),
        None => Budget::SceneMultiple(4),
    };
    let k = opts.passes;
    let reps = opts.power_replicates.unwrap_or(1).max(1);
    let matte_scene = opts.matte_scene.as_deref().unwrap_or(scene);
    // Replicate r renders passes r·K … (r + 1)·K − 1 (seeds seed + r·K + k): replicate 0 is the
    // run without --power. The spp per pass is fixed from the K-pass budget first.
    let plan = |file: &Path, defines: &Vec<(String, String)>, seed: u64| -> Result<PassPlan, String> {
        let one = PassPlan { passes: k, spp: budget, seed, defines: defines.clone(), regions: Vec::new() };
        let spp = if reps > 1 { Budget::PerPass(passes::spp_per_pass(file, &one)?) } else { budget };
        Ok(PassPlan { passes: k * reps, spp, ..one })
    };
    let n = k * reps;
    // The Rust renderer's film weights samples as the reference does (Mitsuba's scalar and JIT
    // variants differ at sharp edges; `docs/validation.md`).
    let splat = match reference {
        Renderer::Mitsuba(variant) => SplatWeights::of_mitsuba_variant(variant),
        Renderer::Matte => SplatWeights::default(),
    };
    let a: Side = passes::rust_side(matte_scene, &plan(matte_scene, &opts.matte_defines, opts.seed)?, splat, &|i| {
        progress("matte", i, n)
    })?;
    let ref_plan = plan(scene, &opts.reference_defines, opts.seed + 1_000_003)?;
    let b: Side = match reference {
        Renderer::Mitsuba(variant) => {
            passes::mitsuba_side_installed(scene, variant, &ref_plan, &dir.join("mitsuba_work"), &|i| {
                progress(variant, i, n)
            })?
        }
        Renderer::Matte => {
            let mut s = passes::rust_side(scene, &ref_plan, splat, &|i| progress("matte (reference)", i, n))?;
            s.label = "matte (other seeds)".into();
            s
        }
    };
    let (a, a_reps) = replicates(a, k)?;
    let (b, b_reps) = replicates(b, k)?;
    let comparison = stats::compare(&a.images, &a.moments, &b.images, &b.moments, opts.alpha)?;
    let power = if reps > 1 {
        Some(power::calibrate(&a_reps, &b_reps, opts.alpha, &|m| progress(&format!("power: {m}"), n, n))?)
    } else {
        None
    };
    let predicted_power = predicted_power::predict(&a.images, &b.images, opts.alpha)?;
    let files = validation_report::write_scene_files(&opts.out, &rel_dir, &a, &b, &comparison)?;
    Ok(SceneResult {
        scene: scene.to_path_buf(),
        name,
        reference: ref_label,
        comparison,
        seconds_matte: a.seconds,
        seconds_reference: b.seconds,
        passes: opts.passes,
        spp_per_pass: a.spp,
        power,
        predicted_power,
        files,
    })
}

/// Splits a side rendered with R × K passes into R replicates of K passes; returns
/// replicate 0 as a side (render time per replicate) and all replicates' images.
fn replicates(side: Side, k: u32) -> Result<(Side, Vec<Vec<matte_render::film::Image>>), String> {
    let reps = side.images.len() / k.max(1) as usize;
    let seconds = side.seconds / reps.max(1) as f64;
    let all: Vec<Vec<_>> = side.images.chunks_exact(k as usize).map(|c| c.to_vec()).collect();
    let first = all.first().cloned().ok_or("no passes")?;
    let s = passes::side_from_images(first, &[], seconds, side.spp, side.label)?;
    Ok((s, if reps > 1 { all } else { Vec::new() }))
}

/// Every `*.xml` directly in `dir`, sorted.
pub fn bundled_scenes(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    v.sort();
    Ok(v)
}

/// Writes the mean images as EXR and tone-mapped PNG.
pub(crate) fn write_mean(dir: &Path, stem: &str, side: &Side) -> Result<(), String> {
    let img = side.moments.mean_image();
    image_io::write_exr(&dir.join(format!("{stem}.exr")), &img)?;
    image_io::write_png(&dir.join(format!("{stem}.png")), &img)
}
