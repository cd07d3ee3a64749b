//! `study.json` and `report.html`. The page has one section per kind of result, each in its
//! own file with both its JSON and its HTML: the main run per scene ([`scenes`]: strips,
//! heatmaps, ratios to Lambert under global and direct lighting), the model variants
//! ([`variants_section`]), the models against their true surfaces ([`truth_section`]) and the
//! convergence series ([`convergence_section`], with its plot in [`plot`]). The true-surface
//! part is also written on its own as `truth.json`.

pub mod convergence_section;
pub mod perceptual_section;
pub mod plot;
pub mod scenes;
pub mod truth_section;
pub mod variants_section;

use super::Study;
use askama::Template;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// study.json.
#[derive(Serialize)]
pub struct StudyJson {
    /// "matte" or "mitsuba <variant>".
    pub renderer: String,
    pub passes: u32,
    pub spp: u32,
    pub answers: Vec<String>,
    pub scenes: Vec<scenes::SceneJson>,
    pub variants: Vec<variants_section::VariantsJson>,
    /// The rough models against the surfaces they describe.
    pub truths: truth_section::TruthsJson,
    pub convergence: Vec<convergence_section::SeriesJson>,
    /// HDR-FLIP against Lambert and the surfaces, with noise floors and intervals.
    pub perceptual: perceptual_section::PerceptualJson,
}

/// A region's ratio to Lambert in both lightings.
#[derive(Serialize)]
pub struct RegionJson {
    pub name: String,
    pub ratio_global: f64,
    pub ratio_global_ci99: f64,
    pub ratio_direct: f64,
    pub ratio_direct_ci99: f64,
}

impl RegionJson {
    /// Pairs the regions of one image under global and direct lighting.
    pub fn pair(global: &[super::ratio::RegionRatio], direct: &[super::ratio::RegionRatio]) -> Vec<RegionJson> {
        global
            .iter()
            .zip(direct)
            .map(|(g, d)| RegionJson {
                name: g.name.clone(),
                ratio_global: g.ratio.value,
                ratio_global_ci99: g.ratio.half_width,
                ratio_direct: d.ratio.value,
                ratio_direct_ci99: d.ratio.half_width,
            })
            .collect()
    }
}

/// A strip image and its heatmap strip for one lighting.
#[derive(Serialize)]
pub struct StripJson {
    pub lighting: &'static str,
    pub strip: std::path::PathBuf,
    pub difference: std::path::PathBuf,
    /// Colour-scale half-range of the heatmap (relative difference).
    pub difference_range: f32,
}

pub fn json(study: &Study) -> StudyJson {
    StudyJson {
        renderer: study.renderer.clone(),
        passes: study.passes,
        spp: study.spp,
        answers: super::answers::answers(study),
        scenes: study.scenes.iter().map(scenes::json).collect(),
        variants: study.variants.iter().map(variants_section::json).collect(),
        truths: truth_section::json(&study.truths),
        convergence: study.convergence.iter().map(convergence_section::json).collect(),
        perceptual: perceptual_section::json(&study.perceptual, &study.perceptual_notes),
    }
}

/// `value ± half-width` with four decimals, the tables' cell.
pub(super) fn ci(r: &super::ratio::Ratio) -> String {
    format!("{:.4} ± {:.4}", r.value, r.half_width)
}

/// report.html: what the numbers mean, the answers, then the sections in order.
#[derive(Template)]
#[template(path = "study_report.html")]
struct ReportHtml<'a> {
    renderer: &'a str,
    passes: u32,
    spp: u32,
    answers: Vec<String>,
    /// The sections, rendered by their own templates.
    sections: Vec<String>,
}

/// report.html; `slices` are the BRDF slice plots copied next to it (relative to it).
pub fn html(study: &Study, slices: &[PathBuf]) -> askama::Result<String> {
    let mut sections = Vec::new();
    if !study.truths.is_empty() {
        sections.push(truth_section::html(&study.truths, slices)?);
    }
    if !study.perceptual.is_empty() || !study.perceptual_notes.is_empty() {
        let p = &study.perceptual;
        sections.push(perceptual_section::html(p, &study.scenes, &study.truths, &study.perceptual_notes)?);
    }
    for s in &study.scenes {
        sections.push(scenes::html(s)?);
    }
    for v in &study.variants {
        sections.push(variants_section::html(v)?);
    }
    for s in &study.convergence {
        let v = study.variants.iter().find(|v| v.scene_name == s.scene_name);
        sections.push(convergence_section::html(s, v)?);
    }
    let answers = super::answers::answers(study);
    ReportHtml { renderer: &study.renderer, passes: study.passes, spp: study.spp, answers, sections }.render()
}

/// study.json, truth.json and report.html in `out`; the BRDF slices copied from `slices`.
pub fn write(out: &Path, study: &Study, slices: Option<&Path>) -> Result<(), String> {
    let j = json(study);
    let text = serde_json::to_string_pretty(&j).map_err(|e| e.to_string())?;
    std::fs::write(out.join("study.json"), text).map_err(|e| e.to_string())?;
    let truth = serde_json::to_string_pretty(&serde_json::json!({
        "renderer": j.renderer, "passes": j.passes, "spp": j.spp, "truths": j.truths,
    }))
    .map_err(|e| e.to_string())?;
    std::fs::write(out.join("truth.json"), truth).map_err(|e| e.to_string())?;
    let slices = match slices {
        Some(from) if !study.truths.is_empty() => truth_section::copy_slices(from, out),
        _ => Vec::new(),
    };
    let page = html(study, &slices).map_err(|e| format!("report.html: {e}"))?;
    std::fs::write(out.join("report.html"), page).map_err(|e| e.to_string())
}
