//! `matte validate`: the Rust renderer against the installed Mitsuba, per pixel, with heatmaps and a
//! report. Exit status 1 and the failing scenes on stderr when any scene disagrees.

use super::render_cmd::parse_defines;
use crate::validate::passes::Renderer;
use crate::validate::{self, SceneResult, ValidateOptions};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct ValidateArgs {
    /// Scene files (Mitsuba XML), or names of bundled scenes (`cornell_box`, `sphere_eon`, …).
    pub scenes: Vec<PathBuf>,
    /// Every bundled scene (the `scenes` folder of the installed matte_mitsuba package): a
    /// self-test of the installation against the Mitsuba installed beside it.
    #[arg(long)]
    pub all: bool,
    /// Mitsuba variant(s) to compare with (repeatable). Default: llvm_ad_rgb in Dr.Jit's
    /// default symbolic mode, the fastest Mitsuba on a CPU and what users run; scalar_rgb (or
    /// any other variant of the wheel) on request.
    #[arg(long = "variant", default_values_t = vec!["llvm_ad_rgb".to_string()])]
    pub variants: Vec<String>,
    /// Compare the Rust renderer with itself (other seeds) instead of Mitsuba: a check of the
    /// test's false-positive rate.
    #[arg(long)]
    pub self_check: bool,
    /// Independent passes per renderer (the variances come from them). 32 by measured power
    /// (docs/validation.md#choosing-the-passes).
    #[arg(long, default_value_t = 32)]
    pub passes: u32,
    /// Total samples per pixel per renderer, split over the passes (default: 4× the scene's
    /// sample_count, for power against small differences).
    #[arg(long)]
    pub spp: Option<u32>,
    /// Smaller budget: 8 passes, 64 spp in total.
    #[arg(long)]
    pub quick: bool,
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Family-wise significance level of the tests.
    #[arg(long, default_value_t = 0.01)]
    pub alpha: f64,
    /// Output folder.
    #[arg(short, long, default_value = "validate_out")]
    pub out: PathBuf,
    /// Scene parameter for both renderers (repeatable).
    #[arg(short = 'D', value_name = "NAME=VALUE")]
    pub define: Vec<String>,
    /// Scene parameter for the Rust renderer only (to test the harness's power).
    #[arg(long, value_name = "NAME=VALUE")]
    pub matte_define: Vec<String>,
    /// Scene parameter for the reference renderer only.
    #[arg(long, value_name = "NAME=VALUE")]
    pub reference_define: Vec<String>,
    /// The Rust renderer renders this scene file instead (a modified scene: measures what the
    /// test detects, e.g. one reflectance changed).
    #[arg(long, value_name = "FILE")]
    pub matte_scene: Option<PathBuf>,
    /// Power calibration: render R replicates of each side (R × the budget) and state the
    /// smallest uniform and 16×16-patch relative change detected with 80 % power, and the
    /// rejection rate on identical inputs (docs/validation.md#power).
    #[arg(long)]
    pub power: bool,
    /// Replicates per side for --power.
    #[arg(long, default_value_t = 10, value_name = "R")]
    pub replicates: u32,
    #[arg(short, long)]
    pub quiet: bool,
    /// Also print the JSON summary on stdout (it is always written to summary.json).
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: &ValidateArgs) -> Result<(), String> {
    let mut scenes = crate::installation::scene_arguments(&a.scenes, "");
    let mut sources = Vec::new();
    if !a.scenes.is_empty() {
        sources.push(format!("{} given on the command line", a.scenes.len()));
    }
    if a.all {
        let bundled = crate::installation::scenes_dir()?;
        let found = validate::bundled_scenes(&bundled)?;
        sources.push(format!("{} bundled with matte_mitsuba ({})", found.len(), bundled.display()));
        scenes.extend(found);
    }
    if scenes.is_empty() {
        return Err("no scenes: give scene files or --all".into());
    }
    let both = parse_defines(&a.define)?;
    let mut matte_defines = both.clone();
    matte_defines.extend(parse_defines(&a.matte_define)?);
    let mut reference_defines = both;
    reference_defines.extend(parse_defines(&a.reference_define)?);
    let (passes, spp) = if a.quick { (8, Some(64)) } else { (a.passes, a.spp) };
    if passes < 2 {
        return Err("--passes must be at least 2".into());
    }
    if !(a.alpha > 0.0 && a.alpha < 1.0) {
        return Err("--alpha must be in (0, 1)".into());
    }
    if a.power && a.replicates < 2 {
        return Err("--replicates must be at least 2".into());
    }
    if a.matte_scene.is_some() && scenes.len() != 1 {
        return Err("--matte-scene needs exactly one scene".into());
    }
    let opts = ValidateOptions {
        passes,
        spp,
        seed: a.seed,
        alpha: a.alpha,
        out: a.out.clone(),
        matte_defines,
        reference_defines,
        matte_scene: a.matte_scene.clone(),
        power_replicates: a.power.then_some(a.replicates),
    };
    std::fs::create_dir_all(&a.out).map_err(|e| format!("{}: {e}", a.out.display()))?;
    let references: Vec<Renderer> = if a.self_check {
        vec![Renderer::Matte]
    } else {
        a.variants.iter().map(|v| Renderer::Mitsuba(v.clone())).collect()
    };
    // Mitsuba's side is found before the first render: a missing one is one error, not one per scene.
    let python = if a.self_check { None } else { Some(crate::installation::mitsuba_side()?) };
    let provenance = validate::summary::Provenance {
        matte: env!("CARGO_PKG_VERSION").into(),
        mitsuba: python.as_ref().and_then(|p| p.mitsuba.clone()),
        references: references
            .iter()
            .map(|r| match r {
                Renderer::Mitsuba(v) => format!("mitsuba {v}"),
                Renderer::Matte => "matte (self-check)".into(),
            })
            .collect(),
        python: python.as_ref().map(|p| p.describe()),
        scenes: sources.join("; "),
    };
    let show = !a.quiet && std::io::stderr().is_terminal();
    let mut results: Vec<SceneResult> = Vec::new();
    let mut errors = Vec::new();
    for scene in &scenes {
        for reference in &references {
            let total = passes as u64 * if a.power { a.replicates as u64 } else { 1 };
            let bar = if show { ProgressBar::new(total) } else { ProgressBar::hidden() };
            bar.set_style(
                ProgressStyle::with_template("{msg:50} [{bar:30}] {pos}/{len} passes {elapsed}")
                    .expect("template")
                    .progress_chars("=> "),
            );
            let name = scene.file_name().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
            let progress = |who: &str, k: u32, _n: u32| {
                bar.set_message(format!("{name}: {who}"));
                bar.set_position(k as u64);
            };
            match validate::validate_scene(scene, reference, &opts, &progress) {
                Ok(r) => {
                    bar.finish_and_clear();
                    if !a.quiet {
                        eprintln!("{}", one_line(&name, &r));
                    }
                    results.push(r);
                }
                Err(e) => {
                    bar.finish_and_clear();
                    errors.push(format!("{}: {e}", scene.display()));
                }
            }
        }
    }
    validate::validation_report::write_run(&a.out, &results, &provenance)?;
    if a.json {
        println!("{}", validate::summary::Summary::new(&results, &provenance).to_json());
    }
    let failed: Vec<String> = results
        .iter()
        .filter(|r| !r.comparison.passed())
        .map(|r| format!("{} (vs {})", r.scene.display(), r.reference))
        .collect();
    if !errors.is_empty() || !failed.is_empty() {
        for e in &errors {
            eprintln!("matte: validate: error: {e}");
        }
        if !failed.is_empty() {
            eprintln!("matte: validate: FAILED: {}", failed.join(", "));
        }
        return Err(format!(
            "{} scene(s) failed, {} could not be validated; report: {}",
            failed.len(),
            errors.len(),
            a.out.join("report.html").display()
        ));
    }
    if !a.json {
        println!("all {} comparison(s) passed; report: {}", results.len(), a.out.join("report.html").display());
    }
    Ok(())
}

/// The verdict of one scene on one line: per scale the rejected blocks, the image-mean
/// difference, and with --power what the budget detects.
fn one_line(name: &str, r: &SceneResult) -> String {
    let c = &r.comparison;
    let scales: Vec<String> = c.scales.iter().map(|s| format!("{} {}", s.scale.key(), s.rejected)).collect();
    let mut line = format!(
        "{} {name} vs {}: rejected [{}], mean diff {:.5} {:.5} {:.5} ± {:.5} {:.5} {:.5}",
        if c.passed() { "PASS" } else { "FAIL" },
        r.reference,
        scales.join(", "),
        c.global.diff.x,
        c.global.diff.y,
        c.global.diff.z,
        c.global.ci99.x,
        c.global.ci99.y,
        c.global.ci99.z
    );
    let d = validate::validation_report::percent;
    line += &format!(
        "; predicted 80% power at {} uniform, {} in a 16×16 patch",
        d(r.predicted_power.uniform),
        d(r.predicted_power.patch)
    );
    if let Some(p) = &r.power {
        line += &format!(
            "; measured 80% power at {} uniform, {} in a 16×16 patch; identical inputs rejected {}/{} (matte), {}/{} (reference)",
            d(p.uniform.detected),
            d(p.patch.detected),
            p.identical_matte.rejected,
            p.identical_matte.pairs,
            p.identical_reference.rejected,
            p.identical_reference.pairs
        );
    }
    line
}
