//! The convergence series' section ([`crate::study::convergence`]): is the paper's
//! Oren–Nayar "glow" a converged property of the model, the same in both renderers?
//! A plot and a table of the region ratio per spp level and renderer, and the verdicts.

use super::plot::ratio_over_spp;
use crate::markup::escape;
use crate::study::configuration::{Configuration, SERIES};
use crate::study::convergence::{Point, Series};
use crate::study::variants::VariantStudy;
use crate::study::{Lighting, answers};
use serde::Serialize;
use std::fmt::Write as _;

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

pub fn html(s: &Series, variants: Option<&VariantStudy>) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        r#"<div class="scene"><h2>{}: convergence in the region "{}" (global illumination)</h2>
<p>Is the paper's Oren–Nayar "glow" real or a bias? The region ratio to Lambert is rendered at increasing total spp by matte and by Mitsuba. {} paired passes per level, and each level has its own seeds.
Only the region's pixels are rendered: the film is cropped to x {}…{}, y {}…{} of {}×{} (derived scenes in <code>{}/convergence/</code>). A real effect stays within its 99 % intervals as spp grows, and the two renderers' intervals overlap.
A bias or noise artefact drifts with spp or differs between the renderers.</p>"#,
        escape(&s.scene_name),
        escape(&s.region),
        s.passes,
        s.crop[0],
        s.crop[0] + s.crop[2] - 1,
        s.crop[1],
        s.crop[1] + s.crop[3] - 1,
        s.film[0],
        s.film[1],
        escape(&s.scene_name)
    );
    for n in &s.notes {
        let _ = write!(h, r#"<p class="note">{}</p>"#, escape(n));
    }
    for m in tracked() {
        h.push_str(&ratio_over_spp(s, *m, &format!("{} / Lambert", m.label())));
    }
    h.push_str("<table><tr><th>total spp</th>");
    for m in tracked() {
        for r in &s.renderers {
            let _ = write!(h, "<th>{}, {}</th>", escape(m.label()), escape(r));
        }
        if s.renderers.len() == 2 {
            h.push_str("<th>overlap</th>");
        }
    }
    h.push_str("</tr>");
    for spp in &s.levels {
        let _ = write!(h, "<tr><td>{spp}</td>");
        for m in tracked() {
            let pts: Vec<Option<&Point>> = s.renderers.iter().map(|r| s.point(*m, r, *spp)).collect();
            for p in &pts {
                match p {
                    Some(p) => h.push_str(&super::ratio_cell(p.ratio)),
                    None => h.push_str("<td>–</td>"),
                }
            }
            if let [Some(a), Some(b)] = pts.as_slice() {
                h.push_str(if a.ratio.overlaps(b.ratio) { "<td>yes</td>" } else { "<td><b>no</b></td>" });
            } else if s.renderers.len() == 2 {
                h.push_str("<td>–</td>");
            }
        }
        h.push_str("</tr>");
    }
    h.push_str("</table>");
    if let Some(r) = variants
        .and_then(|v| v.result(Configuration::OrenNayarFull, Lighting::Global))
        .and_then(|r| r.regions.iter().find(|x| x.name == s.region))
    {
        let _ = write!(
            h,
            r#"<p class="small">The model-variant run at the study's full budget (whole image) gives Oren–Nayar full / Lambert = {:.4} ± {:.4} in this region.</p>"#,
            r.ratio.value, r.ratio.half_width
        );
    }
    h.push_str("<ul>");
    for a in answers::convergence_answers(s, variants) {
        let _ = write!(h, "<li>{}</li>", escape(&a));
    }
    h.push_str("</ul></div>");
    h
}
