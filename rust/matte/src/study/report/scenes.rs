//! The main run's section ([`crate::study::main_run`]), per scene: the strips and heatmaps of
//! every model, and per model the luminance ratio to Lambert (99 % CI) under global and
//! direct lighting, the change between them (the paper's question), the edge/flat
//! concentration of the difference, and the named regions' ratios.

use super::shared::{LightingRatios, RegionJson, StripJson};
use crate::study::answers;
use crate::study::configuration::{TRUTHS, main_run};
use crate::study::main_run::{ModelResult, SceneStudy, study_scene};
use crate::study::options::{Lighting, StudyOptions};
use crate::study::section::{JsonObject, Progress, Scene, Section, Study};
use askama::Template;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The main run as a section of the study.
pub struct MainRun;

impl Section for MainRun {
    fn name(&self) -> &'static str {
        "main run"
    }

    fn passes(&self, _scene: &Scene, opts: &StudyOptions) -> u64 {
        ((main_run().len() + TRUTHS.len()) * 2) as u64 * opts.passes as u64
    }

    fn run(&self, scene: &Scene, study: &mut Study, progress: &dyn Progress) -> Result<(), String> {
        let s = study_scene(&scene.path, &study.options, &|what: &str, _: u32| progress.pass(what))?;
        study.scenes.push(s);
        Ok(())
    }

    fn answers(&self, study: &Study) -> Vec<String> {
        answers::scene_answers(&study.scenes)
    }

    fn json(&self, study: &Study, out: &mut JsonObject) -> Result<(), String> {
        out.entry("scenes", &study.scenes.iter().map(json).collect::<Vec<_>>())
    }

    fn html(&self, study: &Study, _out: &Path) -> Result<String, String> {
        study.scenes.iter().map(|s| html(s).map_err(|e| e.to_string())).collect()
    }
}

/// One scene's main run in study.json.
#[derive(Serialize)]
pub struct SceneJson {
    pub scene: PathBuf,
    pub strips: Vec<StripJson>,
    pub models: Vec<ModelJson>,
    /// What could not be rendered, and why.
    pub notes: Vec<String>,
}

/// One model in both lightings.
#[derive(Serialize)]
pub struct ModelJson {
    /// The plugin name.
    pub model: &'static str,
    /// The configuration's key (the two true surfaces share the plugin `tabulated_brdf`).
    pub key: &'static str,
    pub label: &'static str,
    /// Its luminance ratio to Lambert.
    #[serde(flatten)]
    pub ratios: LightingRatios,
    /// The per-pass ratios to Lambert, in seed order.
    pub pass_ratios_global: Vec<f64>,
    pub pass_ratios_direct: Vec<f64>,
    /// |ratio_global − 1| − |ratio_direct − 1|: positive when the difference to Lambert grows
    /// under global illumination.
    pub abs_difference_global_minus_direct: f64,
    pub edge_mean_abs_rel_diff_global: f64,
    pub flat_mean_abs_rel_diff_global: f64,
    pub edge_mean_abs_rel_diff_direct: f64,
    pub flat_mean_abs_rel_diff_direct: f64,
    pub seconds_global: f64,
    pub seconds_direct: f64,
    pub exr_global: PathBuf,
    pub exr_direct: PathBuf,
    pub regions: Vec<RegionJson>,
}

/// Each main-run model, then each true surface, with its global and direct results, in the
/// table's order.
fn both_lightings(s: &SceneStudy) -> impl Iterator<Item = (&ModelResult, &ModelResult)> {
    main_run()
        .into_iter()
        .chain(TRUTHS)
        .filter_map(|m| Some((s.result(m, Lighting::Global)?, s.result(m, Lighting::Direct)?)))
}

/// The paper's question for one model: does the difference to Lambert grow with global
/// illumination?
fn growth(g: &ModelResult, d: &ModelResult) -> f64 {
    (g.ratio.value - 1.0).abs() - (d.ratio.value - 1.0).abs()
}

/// The half-range of a lighting's heatmap strip, for the template.
fn range_of(s: &SceneStudy, l: &Lighting) -> f32 {
    s.difference_range(*l)
}

/// The scene's entry of study.json.
pub fn json(s: &SceneStudy) -> SceneJson {
    SceneJson {
        scene: s.scene.clone(),
        strips: s
            .strips
            .iter()
            .map(|(l, strip, diff)| StripJson {
                lighting: l.name(),
                strip: strip.clone(),
                difference: diff.clone(),
                difference_range: s.difference_range(*l),
            })
            .collect(),
        models: both_lightings(s)
            .map(|(g, d)| ModelJson {
                model: g.model.bsdf(),
                key: g.model.key(),
                label: g.model.label(),
                ratios: LightingRatios::new(g.ratio, d.ratio),
                pass_ratios_global: s.pass_ratios(g),
                pass_ratios_direct: s.pass_ratios(d),
                abs_difference_global_minus_direct: growth(g, d),
                edge_mean_abs_rel_diff_global: g.edge_flat.0,
                flat_mean_abs_rel_diff_global: g.edge_flat.1,
                edge_mean_abs_rel_diff_direct: d.edge_flat.0,
                flat_mean_abs_rel_diff_direct: d.edge_flat.1,
                seconds_global: g.seconds,
                seconds_direct: d.seconds,
                exr_global: g.exr.clone(),
                exr_direct: d.exr.clone(),
                regions: RegionJson::pair(&g.regions, &d.regions),
            })
            .collect(),
        notes: s.notes.clone(),
    }
}

/// The scene's section of report.html.
#[derive(Template)]
#[template(path = "scene.html")]
struct SceneHtml<'a> {
    s: &'a SceneStudy,
    rows: Vec<(&'a ModelResult, &'a ModelResult)>,
    regions: Vec<&'a str>,
}

/// The scene's part of report.html.
pub fn html(s: &SceneStudy) -> askama::Result<String> {
    let regions = s.results.first().map(|r| r.regions.iter().map(|x| x.name.as_str()).collect()).unwrap_or_default();
    SceneHtml { s, rows: both_lightings(s).collect(), regions }.render()
}
