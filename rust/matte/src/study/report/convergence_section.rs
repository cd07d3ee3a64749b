//! The convergence series' section ([`crate::study::convergence`]): is the paper's
//! Oren–Nayar "glow" a converged property of the model, the same in both renderers?
//! A plot and a table of the region ratio per spp level and renderer, and the verdicts.

use super::plot::ratio_over_spp;
use crate::study::answers;
use crate::study::configuration::{Configuration, SERIES};
use crate::study::convergence::{self, Point, Series};
use crate::study::options::{Lighting, StudyOptions};
use crate::study::ratio::RegionRatio;
use crate::study::section::{JsonObject, Progress, Scene, Section, Stage, Study};
use crate::study::variants::VariantStudy;
use askama::Template;
use serde::Serialize;
use std::path::Path;

/// The convergence series as a section of the study: one per region marked
/// `"convergence": true`, after every scene's other sections.
pub struct Convergence;

impl Section for Convergence {
    fn name(&self) -> &'static str {
        "convergence"
    }

    fn stage(&self) -> Stage {
        Stage::AfterScenes
    }

    fn passes(&self, scene: &Scene, opts: &StudyOptions) -> u64 {
        if opts.convergence_spp.is_empty() {
            return 0;
        }
        scene.regions.iter().filter(|r| r.convergence).map(|_| convergence::pass_count(opts)).sum()
    }

    fn run(&self, scene: &Scene, study: &mut Study, progress: &dyn Progress) -> Result<(), String> {
        if study.options.convergence_spp.is_empty() {
            return Ok(());
        }
        for region in scene.regions.iter().filter(|r| r.convergence) {
            let s = convergence::run(&scene.path, &scene.name, region, &study.options, &|what: &str, _: u32| {
                progress.pass(what)
            })?;
            study.convergence.push(s);
        }
        Ok(())
    }

    fn answers(&self, study: &Study) -> Vec<String> {
        let variants = |s: &Series| study.variants.iter().find(|v| v.scene_name == s.scene_name);
        study.convergence.iter().flat_map(|s| answers::convergence_answers(s, variants(s))).collect()
    }

    fn json(&self, study: &Study, out: &mut JsonObject) -> Result<(), String> {
        out.entry("convergence", &study.convergence.iter().map(json).collect::<Vec<_>>())
    }

    fn html(&self, study: &Study, _out: &Path) -> Result<String, String> {
        let variants = |s: &Series| study.variants.iter().find(|v| v.scene_name == s.scene_name);
        study.convergence.iter().map(|s| html(s, variants(s)).map_err(|e| e.to_string())).collect()
    }
}

/// One convergence series in study.json.
#[derive(Serialize)]
pub struct SeriesJson {
    pub scene: String,
    pub region: String,
    pub lighting: &'static str,
    pub film: [u32; 2],
    /// `[x, y, width, height]` in pixels of `film`.
    pub crop: [u32; 4],
    pub passes: u32,
    pub spp_levels: Vec<u32>,
    pub renderers: Vec<String>,
    pub notes: Vec<String>,
    pub points: Vec<PointJson>,
    pub stable_levels: Vec<StabilityJson>,
    pub renderer_agreement: Vec<AgreementJson>,
    pub answers: Vec<String>,
}

/// One model's region ratio at one level in one renderer.
#[derive(Serialize)]
pub struct PointJson {
    pub spp: u32,
    pub renderer: String,
    /// The configuration's key, e.g. `oren_nayar_full`.
    pub model: &'static str,
    pub ratio: f64,
    pub ratio_ci99: f64,
    pub seconds: f64,
}

/// Per renderer: how many levels' intervals overlap the highest level's.
#[derive(Serialize)]
pub struct StabilityJson {
    pub model: &'static str,
    pub per_renderer: Vec<RendererStabilityJson>,
}

/// One renderer's levels that overlap its highest level.
#[derive(Serialize)]
pub struct RendererStabilityJson {
    pub renderer: String,
    pub overlapping_highest: usize,
    pub levels: usize,
}

/// Levels where the two renderers' intervals overlap, of the levels both rendered.
#[derive(Serialize)]
pub struct AgreementJson {
    pub model: &'static str,
    pub overlapping: usize,
    pub levels: usize,
}

/// The configurations whose ratio the series tracks (not Lambert, the denominator).
fn tracked() -> &'static [Configuration] {
    &SERIES[1..]
}

/// The series in study.json.
pub fn json(s: &Series) -> SeriesJson {
    SeriesJson {
        scene: s.scene_name.clone(),
        region: s.region.clone(),
        lighting: Lighting::Global.name(),
        film: s.film,
        crop: s.crop,
        passes: s.passes,
        spp_levels: s.levels.clone(),
        renderers: s.renderers.clone(),
        notes: s.notes.clone(),
        points: s
            .points
            .iter()
            .map(|p| PointJson {
                spp: p.spp,
                renderer: p.renderer.clone(),
                model: p.model.key(),
                ratio: p.ratio.value,
                ratio_ci99: p.ratio.half_width,
                seconds: p.seconds,
            })
            .collect(),
        stable_levels: tracked()
            .iter()
            .map(|m| StabilityJson {
                model: m.key(),
                per_renderer: s
                    .renderers
                    .iter()
                    .map(|r| {
                        let (k, n) = s.stable(*m, r);
                        RendererStabilityJson { renderer: r.clone(), overlapping_highest: k, levels: n }
                    })
                    .collect(),
            })
            .collect(),
        renderer_agreement: tracked()
            .iter()
            .map(|m| {
                let (k, n) = s.agreement(*m);
                AgreementJson { model: m.key(), overlapping: k, levels: n }
            })
            .collect(),
        answers: answers::convergence_answers(s, None),
    }
}

/// The series' section of report.html.
#[derive(Template)]
#[template(path = "convergence.html")]
struct ConvergenceHtml<'a> {
    s: &'a Series,
    plots: Vec<String>,
    tracked: &'static [Configuration],
    /// Per level, per tracked configuration, each renderer's point.
    rows: Vec<(u32, Vec<Vec<Option<&'a Point>>>)>,
    /// Oren–Nayar full's ratio in the region from the variant run, at the full budget.
    full_budget: Option<&'a RegionRatio>,
    answers: Vec<String>,
}

/// The series' part of report.html.
pub fn html(s: &Series, variants: Option<&VariantStudy>) -> askama::Result<String> {
    let points = |spp: u32, m: &Configuration| s.renderers.iter().map(|r| s.point(*m, r, spp)).collect();
    ConvergenceHtml {
        s,
        plots: tracked().iter().map(|m| ratio_over_spp(s, *m, &format!("{} / Lambert", m.label()))).collect(),
        tracked: tracked(),
        rows: s.levels.iter().map(|&spp| (spp, tracked().iter().map(|m| points(spp, m)).collect())).collect(),
        full_budget: variants
            .and_then(|v| v.result(Configuration::OrenNayarFull, Lighting::Global))
            .and_then(|r| r.regions.iter().find(|x| x.name == s.region)),
        answers: answers::convergence_answers(s, variants),
    }
    .render()
}
