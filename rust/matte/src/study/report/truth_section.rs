//! The true-surface section ([`crate::study::truth`]): the answer table model × scene ×
//! lighting (ratio to its own surface, 99 % CI, Δ and whether the difference grows under
//! global illumination), the closest model per scene, the heatmap strips (model − surface) /
//! surface, and the BRDF slices of the models against the simulated surfaces.

use super::shared::LightingRatios;
use crate::study::answers;
use crate::study::configuration::{Configuration, TRUTHS, WITH_TRUTH, main_run};
use crate::study::options::{Lighting, StudyOptions};
use crate::study::ratio::Ratio;
use crate::study::section::{JsonObject, Progress, Scene, Section, Study};
use crate::study::truth::{self, TruthStudy};
use askama::Template;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The models against their true surfaces as a section of the study.
pub struct Truths;

impl Section for Truths {
    fn name(&self) -> &'static str {
        "true surfaces"
    }

    fn passes(&self, scene: &Scene, opts: &StudyOptions) -> u64 {
        truth::pass_count(opts, &scene.name)
    }

    fn run(&self, scene: &Scene, study: &mut Study, progress: &dyn Progress) -> Result<(), String> {
        let variants = study.variants.iter().find(|v| v.scene_name == scene.name);
        let t =
            truth::run(study.scene(&scene.name)?, variants, &study.options, &|what: &str, _: u32| progress.pass(what))?;
        study.truths.extend(t);
        Ok(())
    }

    fn answers(&self, study: &Study) -> Vec<String> {
        let mut out: Vec<String> = answers::truth_summary(&study.truths).into_iter().collect();
        out.extend(study.truths.iter().flat_map(answers::truth_answers));
        out
    }

    fn json(&self, study: &Study, out: &mut JsonObject) -> Result<(), String> {
        out.entry("truths", &json(&study.truths))
    }

    fn json_file(&self) -> Option<&'static str> {
        Some("truth.json")
    }

    fn html(&self, study: &Study, out: &Path) -> Result<String, String> {
        if study.truths.is_empty() {
            return Ok(String::new());
        }
        let slices = match &study.options.truth_slices {
            Some(from) => copy_slices(from, out),
            None => Vec::new(),
        };
        html(&study.truths, &slices).map_err(|e| e.to_string())
    }
}

/// The BRDF slices of `docs/microgeometry/` shown in the section, at the study's roughness 0.3
/// and facet albedo 0.8: per model, the slice through its largest error against its surface
/// (`validation/generators/truth_error_slices.py`), then both surfaces against every model.
pub const SLICES: [&str; 6] = [
    "truth_slice_oren_nayar_qualitative.png",
    "truth_slice_oren_nayar_full.png",
    "truth_slice_eon.png",
    "truth_slice_ginneken.png",
    "slices_v_cavities_r0.3_rho0.8.png",
    "slices_gaussian_height_field_r0.3_rho0.8.png",
];

/// Where the report's copies of [`SLICES`] go, relative to the output folder.
pub fn slices_dir() -> PathBuf {
    PathBuf::from("truth_slices")
}

/// The true surfaces, over every scene.
#[derive(Serialize)]
pub struct TruthsJson {
    /// The surfaces and their tables.
    pub surfaces: Vec<SurfaceJson>,
    /// The models rendered in the main run that describe no simulated surface.
    pub without_surface: Vec<&'static str>,
    pub scenes: Vec<TruthJson>,
}

/// A true surface, its table and the models that describe it.
#[derive(Serialize)]
pub struct SurfaceJson {
    pub key: &'static str,
    pub label: &'static str,
    pub table: &'static str,
    pub models: Vec<&'static str>,
}

/// One scene's models against their surfaces.
#[derive(Serialize)]
pub struct TruthJson {
    pub scene: String,
    /// Global and direct lighting are one image (the scene's own max_depth is 2).
    pub direct_only: bool,
    pub strips: Vec<TruthStripJson>,
    /// Oren–Nayar full's derived scene, when rendered for this comparison.
    pub scene_file: Option<PathBuf>,
    pub comparisons: Vec<ComparisonJson>,
    pub answers: Vec<String>,
}

/// A heatmap strip of the models against their surfaces in one lighting.
#[derive(Serialize)]
pub struct TruthStripJson {
    pub lighting: &'static str,
    /// Heatmap strip (model − surface) / surface.
    pub difference: PathBuf,
    pub difference_range: f32,
}

/// One model against its surface in both lightings.
#[derive(Serialize)]
pub struct ComparisonJson {
    pub model: &'static str,
    pub label: &'static str,
    pub truth: &'static str,
    pub truth_label: &'static str,
    /// Image-mean luminance ratio model / surface (paired passes), 99 % half-width.
    #[serde(flatten)]
    pub ratios: LightingRatios,
    /// The per-pass ratios model / surface, in seed order.
    pub pass_ratios_global: Vec<f64>,
    pub pass_ratios_direct: Vec<f64>,
    /// Δ = |ratio_global − 1| − |ratio_direct − 1| and its 99 % half-width.
    pub growth: f64,
    pub growth_ci99: f64,
    /// `grows`, `shrinks`, `undecided` or `direct only`.
    pub verdict: &'static str,
    /// Rank from the closest to its surface (1) in each lighting.
    pub rank_global: usize,
    pub rank_direct: usize,
}

fn comparisons(t: &TruthStudy) -> Vec<ComparisonJson> {
    let rank = |m: Configuration, l: Lighting| t.ranking(l).iter().position(|c| c.model == m).map_or(0, |i| i + 1);
    t.models()
        .into_iter()
        .filter_map(|m| {
            let g = t.comparison(m, Lighting::Global)?;
            let d = t.comparison(m, Lighting::Direct)?;
            let (delta, verdict) = t.growth(m)?;
            Some(ComparisonJson {
                model: m.key(),
                label: m.label(),
                truth: g.truth.key(),
                truth_label: g.truth.label(),
                ratios: LightingRatios::new(g.ratio, d.ratio),
                pass_ratios_global: g.pass_ratios.clone(),
                pass_ratios_direct: d.pass_ratios.clone(),
                growth: delta.value,
                growth_ci99: delta.half_width,
                verdict: verdict.name(),
                rank_global: rank(m, Lighting::Global),
                rank_direct: rank(m, Lighting::Direct),
            })
        })
        .collect()
}

/// The true surfaces in study.json and truth.json.
pub fn json(truths: &[TruthStudy]) -> TruthsJson {
    TruthsJson {
        surfaces: TRUTHS
            .iter()
            .map(|t| SurfaceJson {
                key: t.key(),
                label: t.label(),
                table: t.table().unwrap_or_default(),
                models: WITH_TRUTH.iter().filter(|m| m.true_surface() == Some(*t)).map(|m| m.key()).collect(),
            })
            .collect(),
        without_surface: without_surface().iter().map(|m| m.key()).collect(),
        scenes: truths
            .iter()
            .map(|t| TruthJson {
                scene: t.scene_name.clone(),
                direct_only: t.direct_only,
                strips: t
                    .strips
                    .iter()
                    .map(|(l, p, r)| TruthStripJson { lighting: l.name(), difference: p.clone(), difference_range: *r })
                    .collect(),
                scene_file: t.scene_file.clone(),
                comparisons: comparisons(t),
                answers: answers::truth_answers(t),
            })
            .collect(),
    }
}

/// The main run's models with no simulated surface.
fn without_surface() -> Vec<Configuration> {
    main_run().into_iter().filter(|m| m.true_surface().is_none()).collect()
}

/// The true-surface section of report.html.
#[derive(Template)]
#[template(path = "truth.html")]
struct TruthHtml<'a> {
    /// Each surface with the models that describe it.
    surfaces: Vec<(Configuration, String)>,
    without_surface: String,
    rows: Vec<(&'a TruthStudy, ComparisonJson)>,
    closest: Vec<String>,
    truths: &'a [TruthStudy],
    slices: &'a [PathBuf],
}

/// `value ± half-width` with the decimals its half-width needs.
fn ci(value: &f64, half_width: &f64) -> String {
    answers::ci(Ratio::new(*value, *half_width))
}

/// The section; `slices` are the copied slice plots (relative to the output folder).
pub fn html(truths: &[TruthStudy], slices: &[PathBuf]) -> askama::Result<String> {
    let labels = |ms: &mut dyn Iterator<Item = &Configuration>| ms.map(|m| m.label()).collect::<Vec<_>>().join(", ");
    TruthHtml {
        surfaces: TRUTHS
            .into_iter()
            .map(|t| (t, labels(&mut WITH_TRUTH.iter().filter(|m| m.true_surface() == Some(t)))))
            .collect(),
        without_surface: labels(&mut without_surface().iter()),
        rows: truths.iter().flat_map(|t| comparisons(t).into_iter().map(move |c| (t, c))).collect(),
        closest: truths.iter().flat_map(answers::closest_answers).collect(),
        truths,
        slices,
    }
    .render()
}

/// Copies [`SLICES`] from `source` (the installed package's `truth_slices/`, copies of
/// `docs/microgeometry/`'s made by the wheel's build) into the output folder; returns the
/// copies (relative to `out`) that exist.
pub fn copy_slices(source: &Path, out: &Path) -> Vec<PathBuf> {
    let dir = out.join(slices_dir());
    SLICES
        .iter()
        .filter_map(|name| {
            let src = Some(source.join(name)).filter(|p| p.is_file())?;
            std::fs::create_dir_all(&dir).ok()?;
            std::fs::copy(&src, dir.join(name)).ok()?;
            Some(slices_dir().join(name))
        })
        .collect()
}
