//! `matte study`: the seed paper's scenes × models, strips, heatmaps and the measured answer
//! to its question (report.html + study.json); then the model variants and the convergence
//! series of the regions that ask for one.

use super::render_cmd::parse_defines;
use crate::study::{self, Study, StudyOptions, convergence, perceptual, truth, variants};
use crate::validate::passes::Renderer;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct StudyArgs {
    /// Scene files, or names of the bundled study scenes (`cornell`, `bunny`, `curved`,
    /// `room`); default: all four.
    pub scenes: Vec<PathBuf>,
    /// Renderer: matte (default) or mitsuba.
    #[arg(long, default_value = "matte")]
    pub renderer: String,
    /// Mitsuba variant when --renderer mitsuba.
    #[arg(long, default_value = "scalar_rgb")]
    pub variant: String,
    /// Paired passes per image (for the confidence intervals).
    #[arg(long, default_value_t = 8)]
    pub passes: u32,
    /// Total samples per pixel per image, split over the passes.
    #[arg(long, default_value_t = 128)]
    pub spp: u32,
    /// Film width (the scenes' `res` parameter).
    #[arg(long)]
    pub res: Option<u32>,
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Scene parameter (repeatable).
    #[arg(short = 'D', value_name = "NAME=VALUE")]
    pub define: Vec<String>,
    /// Scenes (file stems, comma-separated, or `all`) whose model variants are rendered:
    /// Wolff normal and raw, Oren–Nayar full.
    #[arg(long, default_value = "cornell", value_delimiter = ',')]
    pub variant_scenes: Vec<String>,
    /// Skip the model variants.
    #[arg(long)]
    pub no_variants: bool,
    /// Total spp of each level of the convergence series (comma-separated), for the regions
    /// marked `"convergence": true` in `<scene>.regions.json`.
    #[arg(long, default_value = "16,64,256,1024,4096", value_delimiter = ',')]
    pub convergence_spp: Vec<u32>,
    /// Skip the convergence series.
    #[arg(long)]
    pub no_convergence: bool,
    /// Skip the perceptual differences (HDR-FLIP with its noise floor, computed by the
    /// `flip-evaluator` package in the Python side).
    #[arg(long)]
    pub no_perceptual: bool,
    #[arg(short, long, default_value = "study_out")]
    pub out: PathBuf,
    #[arg(short, long)]
    pub quiet: bool,
}

pub fn run(a: &StudyArgs) -> Result<(), String> {
    let renderer = match a.renderer.as_str() {
        "matte" => Renderer::Matte,
        "mitsuba" => Renderer::Mitsuba(a.variant.clone()),
        other => return Err(format!("--renderer must be matte or mitsuba, got \"{other}\"")),
    };
    if a.passes < 2 || a.spp < a.passes {
        return Err("need --passes ≥ 2 and --spp ≥ --passes".into());
    }
    let scenes = if a.scenes.is_empty() {
        study::study_scenes()?
    } else {
        crate::installation::scene_arguments(&a.scenes, "study")
    };
    if scenes.is_empty() {
        return Err("no study scenes found".into());
    }
    std::fs::create_dir_all(&a.out).map_err(|e| format!("{}: {e}", a.out.display()))?;
    if !a.no_convergence && a.convergence_spp.iter().any(|&s| s < a.passes) {
        return Err(format!("every --convergence-spp level must be ≥ --passes ({})", a.passes));
    }
    let opts = StudyOptions {
        out: a.out.clone(),
        passes: a.passes,
        spp: a.spp,
        seed: a.seed,
        res: a.res,
        renderer,
        defines: parse_defines(&a.define)?,
        variant_scenes: if a.no_variants { Vec::new() } else { a.variant_scenes.clone() },
        convergence_spp: if a.no_convergence { Vec::new() } else { a.convergence_spp.clone() },
        mitsuba_variant: a.variant.clone(),
        ground_truth: crate::installation::package_dir()?.join("ground_truth"),
        truth_slices: crate::installation::package_data("truth_slices").ok(),
        perceptual: !a.no_perceptual,
    };
    // Progress total: main run (models and true surfaces), variants, true-surface comparison,
    // convergence series, the perceptual step's noise floor.
    let per_scene = study::configuration::main_run().len() + study::configuration::TRUTHS.len();
    let mut total = (scenes.len() * per_scene * 2) as u64 * a.passes as u64;
    total += scenes.len() as u64 * perceptual::pass_count(&opts);
    let mut series_regions = Vec::new();
    for scene in &scenes {
        let name = scene.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        if opts.variants_for(&name) {
            total += variants::pass_count(a.passes);
        }
        total += truth::pass_count(&opts, &name);
        if !opts.convergence_spp.is_empty() {
            for r in study::load_regions(scene)
                .map_err(|e| format!("{}: {e}", scene.display()))?
                .into_iter()
                .filter(|r| r.convergence)
            {
                total += convergence::pass_count(&opts);
                series_regions.push((scene.clone(), name.clone(), r));
            }
        }
    }
    let bar = if !a.quiet && std::io::stderr().is_terminal() { ProgressBar::new(total) } else { ProgressBar::hidden() };
    bar.set_style(
        ProgressStyle::with_template("{msg:40} [{bar:30}] {pos}/{len} passes {elapsed} (eta {eta})")
            .expect("template")
            .progress_chars("=> "),
    );
    let progress = |what: &str, _k: u32| {
        bar.set_message(what.to_string());
        bar.inc(1);
    };
    let mut studies = Vec::new();
    let mut variant_studies = Vec::new();
    let mut truth_studies = Vec::new();
    let mut perceptual_studies = Vec::new();
    let mut perceptual_notes = Vec::new();
    for scene in &scenes {
        let s = study::study_scene(scene, &opts, &progress).map_err(|e| format!("{}: {e}", scene.display()))?;
        let v = if opts.variants_for(&s.name) {
            Some(variants::run(&s, &opts, &progress).map_err(|e| format!("{}: variants: {e}", scene.display()))?)
        } else {
            None
        };
        let t = truth::run(&s, v.as_ref(), &opts, &progress)
            .map_err(|e| format!("{}: true surfaces: {e}", scene.display()))?;
        if opts.perceptual {
            bar.set_message(format!("{} HDR-FLIP", s.name));
            match perceptual::run(&s, t.as_ref(), &opts) {
                Ok(p) => perceptual_studies.push(p),
                Err(e) => {
                    perceptual_notes.push(format!("{}: the perceptual differences were not computed: {e}", s.name))
                }
            }
        }
        truth_studies.extend(t);
        variant_studies.extend(v);
        studies.push(s);
    }
    let mut series = Vec::new();
    for (scene, name, region) in &series_regions {
        series.push(
            convergence::run(scene, name, region, &opts, &progress)
                .map_err(|e| format!("{}: convergence: {e}", scene.display()))?,
        );
    }
    bar.finish_and_clear();
    let label = match &opts.renderer {
        Renderer::Matte => "matte".to_string(),
        Renderer::Mitsuba(v) => format!("mitsuba {v}"),
    };
    let study = Study {
        renderer: label,
        passes: a.passes,
        spp: a.spp,
        scenes: studies,
        variants: variant_studies,
        truths: truth_studies,
        convergence: series,
        perceptual: perceptual_studies,
        perceptual_notes,
    };
    study::report::write(&a.out, &study, opts.truth_slices.as_deref())?;
    println!("{}", serde_json::to_string_pretty(&study::report::json(&study)).expect("json"));
    Ok(())
}
