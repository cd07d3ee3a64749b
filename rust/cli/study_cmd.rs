//! `matte study`: the seed paper's scenes × models, strips, heatmaps and the measured answer
//! to its question (report.html + study.json).

use super::render_cmd::parse_defines;
use crate::study::{self, Options};
use crate::validate::Reference;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct StudyArgs {
    /// Scene files (default: every scene in mitsuba_scenes/study/).
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
    #[arg(short, long, default_value = "study_out")]
    pub out: PathBuf,
    #[arg(short, long)]
    pub quiet: bool,
}

pub fn run(a: &StudyArgs) -> Result<(), String> {
    let renderer = match a.renderer.as_str() {
        "matte" => Reference::Matte,
        "mitsuba" => Reference::Mitsuba(a.variant.clone()),
        other => return Err(format!("--renderer must be matte or mitsuba, got \"{other}\"")),
    };
    if a.passes < 2 || a.spp < a.passes {
        return Err("need --passes ≥ 2 and --spp ≥ --passes".into());
    }
    let scenes = if a.scenes.is_empty() { study::study_scenes()? } else { a.scenes.clone() };
    if scenes.is_empty() {
        return Err("no study scenes found".into());
    }
    std::fs::create_dir_all(&a.out).map_err(|e| format!("{}: {e}", a.out.display()))?;
    let opts = Options { out: a.out.clone(), passes: a.passes, spp: a.spp, seed: a.seed, res: a.res, renderer, defines: parse_defines(&a.define)? };
    let total = (scenes.len() * study::MODELS.len() * 2) as u64 * a.passes as u64;
    let bar = if !a.quiet && std::io::stderr().is_terminal() { ProgressBar::new(total) } else { ProgressBar::hidden() };
    bar.set_style(ProgressStyle::with_template("{msg:40} [{bar:30}] {pos}/{len} passes {elapsed} (eta {eta})").expect("template").progress_chars("=> "));
    let mut studies = Vec::new();
    for scene in &scenes {
        let s = study::study_scene(scene, &opts, &|what, _k| {
            bar.set_message(what.to_string());
            bar.inc(1);
        })
        .map_err(|e| format!("{}: {e}", scene.display()))?;
        studies.push(s);
    }
    bar.finish_and_clear();
    let label = match &opts.renderer {
        Reference::Matte => "matte".to_string(),
        Reference::Mitsuba(v) => format!("mitsuba {v}"),
    };
    study::report::write(&a.out, &studies, &label, a.passes, a.spp)?;
    println!("{}", serde_json::to_string_pretty(&study::report::json(&studies, &label, a.passes, a.spp)).expect("json"));
    Ok(())
}
