//! `matte study`: parses the arguments, runs the study ([`crate::study::run`]), writes
//! report.html and study.json, and prints the answer sentences and where the report is (with
//! `--json`, study.json instead).

use super::render_cmd::parse_defines;
use crate::study::{self, StudyOptions};
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
    /// Seed of the first pass (pass k uses seed + k).
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
    /// Output folder: report.html, study.json, truth.json and the pictures.
    #[arg(short, long, default_value = "study_out")]
    pub out: PathBuf,
    /// Hide the progress bar.
    #[arg(short, long)]
    pub quiet: bool,
    /// Print study.json on stdout instead of the answers (it is always written to the output
    /// folder).
    #[arg(long)]
    pub json: bool,
}

/// The progress bar on stderr.
impl study::Progress for ProgressBar {
    fn start(&self, total: u64) {
        self.set_length(total);
    }
    fn pass(&self, what: &str) {
        self.set_message(what.to_string());
        self.inc(1);
    }
    fn step(&self, what: &str) {
        self.set_message(what.to_string());
    }
}

/// Runs the study, writes study.json and report.html, and prints the answers and where the
/// report is (or, with `--json`, study.json).
pub fn run(a: &StudyArgs) -> Result<(), String> {
    let renderer = match a.renderer.as_str() {
        "matte" => Renderer::Matte,
        "mitsuba" => Renderer::Mitsuba(a.variant.clone()),
        other => return Err(format!("--renderer must be matte or mitsuba, got \"{other}\"")),
    };
    if a.passes < 2 || a.spp < a.passes {
        return Err("need --passes ≥ 2 and --spp ≥ --passes".into());
    }
    if !a.no_convergence && a.convergence_spp.iter().any(|&s| s < a.passes) {
        return Err(format!("every --convergence-spp level must be ≥ --passes ({})", a.passes));
    }
    let scenes = if a.scenes.is_empty() {
        study::study_scenes()?
    } else {
        crate::installation::scene_arguments(&a.scenes, "study")
    };
    if scenes.is_empty() {
        return Err("no study scenes found".into());
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
    let bar = if !a.quiet && std::io::stderr().is_terminal() { ProgressBar::new(0) } else { ProgressBar::hidden() };
    bar.set_style(
        ProgressStyle::with_template("{msg:40} [{bar:30}] {pos}/{len} passes {elapsed} (eta {eta})")
            .expect("template")
            .progress_chars("=> "),
    );
    let result = study::run(&scenes, &opts, &bar);
    bar.finish_and_clear();
    let study = result?;
    study::report::write(&study)?;
    if a.json {
        println!("{}", study::report::json(&study)?);
    } else {
        for answer in study::report::answers(&study) {
            println!("{answer}");
        }
        println!(
            "report: {} (the numbers: {})",
            a.out.join("report.html").display(),
            a.out.join("study.json").display()
        );
    }
    Ok(())
}
