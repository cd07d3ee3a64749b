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

use super::{Lighting, Study};
use crate::markup::escape;
use serde::Serialize;
use std::fmt::Write as _;
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

/// One lighting's strip and heatmap strip with the heatmap's colour scale (`what` − Lambert).
pub(super) fn strips_html(l: Lighting, strip: &Path, diff: &Path, range: f32, what: &str) -> String {
    format!(
        r#"<h3>{} lighting</h3><img src="{}"><br><img src="{}"><p>Heatmap: ({what} − Lambert) / Lambert, blue −{:.0} % … red +{:.0} %.</p>"#,
        l.name(),
        escape(&strip.display().to_string()),
        escape(&diff.display().to_string()),
        range * 100.0,
        range * 100.0
    )
}

/// `value ± half-width` in a table cell.
pub(super) fn ratio_cell(r: super::ratio::Ratio) -> String {
    format!("<td>{:.4} ± {:.4}</td>", r.value, r.half_width)
}

/// report.html; `slices` are the BRDF slice plots copied next to it (relative to it).
pub fn html(study: &Study, slices: &[PathBuf]) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        r#"<!doctype html><html><head><meta charset="utf-8"><title>matte study</title><style>
body{{font-family:system-ui,sans-serif;margin:24px;color:#222;max-width:1400px}} img{{max-width:100%;border:1px solid #ddd}}
table{{border-collapse:collapse;font-size:14px;margin:8px 0;display:block;overflow-x:auto;max-width:100%}} td,th{{padding:3px 10px;border-bottom:1px solid #eee;text-align:right}} td{{white-space:nowrap}}
th:first-child,td:first-child{{text-align:left}} .scene{{border-top:1px solid #ccc;padding-top:12px;margin-top:16px}}
.note{{background:#fff4d6;border-left:4px solid #e0a800;padding:6px 10px}} td.l{{text-align:left}} .small{{font-size:13px;color:#555}}
</style></head><body><h1>matte study: diffuse models under global illumination</h1>
<p>Renderer: {renderer}; {passes} passes, {spp} spp per image in total; every model uses the same seeds (paired passes).
Ratio = image-mean luminance of the model / Lambert, ± 99 % confidence interval from the paired per-pass ratios.
"Global" is the scene's path depth, "direct" is max_depth 2. Δ = |ratio<sub>global</sub> − 1| − |ratio<sub>direct</sub> − 1|:
positive = the difference to Lambert grows under global illumination. Edge/flat = mean |relative luminance difference| to
Lambert on the 10 % of pixels with the strongest gradient of Lambert's image vs on the others.</p>"#,
        renderer = escape(&study.renderer),
        passes = study.passes,
        spp = study.spp,
    );
    h.push_str("<h2>Answers, computed from the measurements below</h2><ul>");
    for a in super::answers::answers(study) {
        let _ = write!(h, "<li>{}</li>", escape(&a));
    }
    h.push_str("</ul>");
    if !study.truths.is_empty() {
        h.push_str(&truth_section::html(&study.truths, slices));
    }
    if !study.perceptual.is_empty() || !study.perceptual_notes.is_empty() {
        h.push_str(&perceptual_section::html(&study.perceptual, &study.scenes, &study.truths, &study.perceptual_notes));
    }
    for s in &study.scenes {
        h.push_str(&scenes::html(s));
    }
    for v in &study.variants {
        h.push_str(&variants_section::html(v));
    }
    for s in &study.convergence {
        h.push_str(&convergence_section::html(s, study.variants.iter().find(|v| v.scene_name == s.scene_name)));
    }
    h.push_str("</body></html>\n");
    h
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
    std::fs::write(out.join("report.html"), html(study, &slices)).map_err(|e| e.to_string())
}
