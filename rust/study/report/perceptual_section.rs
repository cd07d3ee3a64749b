//! The perceptual section ([`crate::study::perceptual`]): per scene and lighting, the FLIP
//! maps beside the signed heatmaps (with the colour bar), a table of the mean and the 95th
//! percentile of HDR-FLIP with their 99 % jackknife intervals and the noise floor, and the
//! verdicts (more or less visible under global illumination, against the energy verdict).

use crate::markup::escape;
use crate::study::configuration::Configuration;
use crate::study::perceptual::{Answer, Comparison, Exposure, FlipPair, PerceptualStudy};
use crate::study::ratio::Ratio;
use crate::study::truth::TruthStudy;
use crate::study::{Lighting, SceneStudy, answers};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[derive(Serialize)]
pub struct PerceptualJson {
    /// The metric and how every value is computed.
    pub metric: &'static str,
    pub scenes: Vec<SceneJson>,
    /// Scenes without perceptual values, and why.
    pub notes: Vec<String>,
}

#[derive(Serialize)]
pub struct SceneJson {
    pub scene: String,
    /// "flip-evaluator <version>".
    pub implementation: String,
    /// Wall time of the HDR-FLIP evaluations.
    pub seconds: f64,
    pub direct_only: bool,
    pub exposure: Vec<ExposureJson>,
    pub noise_floor: Vec<FloorJson>,
    pub strips: Vec<StripJson>,
    pub comparisons: Vec<ComparisonJson>,
    pub answers: Vec<AnswerJson>,
}

#[derive(Serialize)]
pub struct ExposureJson {
    pub lighting: &'static str,
    #[serde(flatten)]
    pub exposure: Exposure,
}

#[derive(Serialize)]
pub struct FloorJson {
    pub lighting: &'static str,
    #[serde(flatten)]
    pub flip: FlipJson,
}

/// Mean and 95th percentile of a FLIP map with their 99 % jackknife half-widths and the
/// leave-one-out values (pass k left out of both images).
#[derive(Serialize)]
pub struct FlipJson {
    pub mean: f64,
    pub mean_ci99: f64,
    pub p95: f64,
    pub p95_ci99: f64,
    pub jackknife_mean: Vec<f64>,
    pub jackknife_p95: Vec<f64>,
}

impl FlipJson {
    fn of(f: &FlipPair) -> FlipJson {
        FlipJson {
            mean: f.mean.value.value,
            mean_ci99: f.mean.value.half_width,
            p95: f.p95.value.value,
            p95_ci99: f.p95.value.half_width,
            jackknife_mean: f.mean.replicates.clone(),
            jackknife_p95: f.p95.replicates.clone(),
        }
    }
}

#[derive(Serialize)]
pub struct StripJson {
    pub lighting: &'static str,
    /// FLIP maps against Lambert (the noise floor's first).
    pub flip_against_lambert: PathBuf,
    /// FLIP maps of the rough models against their surfaces.
    pub flip_against_surface: Option<PathBuf>,
}

#[derive(Serialize)]
pub struct ComparisonJson {
    /// The configuration's key (`eon`, `truth_v_cavities`, …).
    pub model: &'static str,
    /// `lambert` or the surface's key.
    pub reference: &'static str,
    pub lighting: &'static str,
    #[serde(flatten)]
    pub flip: FlipJson,
    /// The same lighting's noise floor (mean and 95th percentile of Lambert against Lambert
    /// with other seeds).
    pub noise_floor_mean: f64,
    pub noise_floor_p95: f64,
    /// The mean's interval lies entirely above the noise floor's.
    pub above_noise_floor: bool,
}

#[derive(Serialize)]
pub struct AnswerJson {
    pub model: &'static str,
    pub reference: &'static str,
    /// Mean FLIP global − direct, paired jackknife 99 % half-width.
    pub flip_global_minus_direct: f64,
    pub flip_global_minus_direct_ci99: f64,
    /// more visible, less visible, undecided, within the noise, direct only.
    pub visibility: &'static str,
    /// Δ = |r_global − 1| − |r_direct − 1| of the luminance ratios, 99 % half-width, verdict.
    pub energy_delta: f64,
    pub energy_delta_ci99: f64,
    pub energy_verdict: &'static str,
    /// agree, disagree, energy only, perceptual only, neither decided.
    pub agreement: &'static str,
}

pub const METRIC: &str = "HDR-FLIP (flip-evaluator, NVIDIA's reference implementation) of the two mean images of a pair; one exposure range per scene and lighting, derived by HDR-FLIP from that lighting's Lambert image (ACES tone mapping, 67 pixels per degree); intervals: 99 % jackknife over the passes (pass k left out of both images); noise floor: Lambert against Lambert rendered with other seeds at the same budget";

fn floor_of(p: &PerceptualStudy, l: Lighting) -> (f64, f64) {
    p.floor(l).map_or((f64::NAN, f64::NAN), |f| (f.mean.value.value, f.p95.value.value))
}

pub fn json(studies: &[PerceptualStudy], notes: &[String]) -> PerceptualJson {
    PerceptualJson {
        metric: METRIC,
        scenes: studies
            .iter()
            .map(|p| SceneJson {
                scene: p.scene_name.clone(),
                implementation: p.implementation.clone(),
                seconds: p.seconds,
                direct_only: p.direct_only,
                exposure: p
                    .exposures
                    .iter()
                    .map(|(l, e)| ExposureJson { lighting: l.name(), exposure: e.clone() })
                    .collect(),
                noise_floor: p
                    .floors
                    .iter()
                    .map(|(l, f)| FloorJson { lighting: l.name(), flip: FlipJson::of(f) })
                    .collect(),
                strips: p
                    .strips
                    .iter()
                    .map(|(l, a, s)| StripJson {
                        lighting: l.name(),
                        flip_against_lambert: a.clone(),
                        flip_against_surface: s.clone(),
                    })
                    .collect(),
                comparisons: p
                    .comparisons
                    .iter()
                    .map(|c| {
                        let (fm, fp) = floor_of(p, c.lighting);
                        ComparisonJson {
                            model: c.model.key(),
                            reference: c.reference.key(),
                            lighting: c.lighting.name(),
                            flip: FlipJson::of(&c.flip),
                            noise_floor_mean: fm,
                            noise_floor_p95: fp,
                            above_noise_floor: p.above_floor(c),
                        }
                    })
                    .collect(),
                answers: p.answers.iter().map(answer_json).collect(),
            })
            .collect(),
        notes: notes.to_vec(),
    }
}

fn answer_json(a: &Answer) -> AnswerJson {
    AnswerJson {
        model: a.model.key(),
        reference: a.reference.key(),
        flip_global_minus_direct: a.delta.value,
        flip_global_minus_direct_ci99: a.delta.half_width,
        visibility: a.visibility.name(),
        energy_delta: a.energy.value,
        energy_delta_ci99: a.energy.half_width,
        energy_verdict: a.energy_verdict.name(),
        agreement: a.agreement.name(),
    }
}

/// `value ± half-width` with three significant digits of FLIP.
fn flip_cell(r: Ratio) -> String {
    format!("<td>{:.4} ± {:.4}</td>", r.value, r.half_width)
}

/// The colour bar of the FLIP maps in HTML: magma, 0 … 1.
fn colour_bar() -> String {
    let stops: Vec<String> = (0..=10)
        .map(|i| {
            let c = colorous::MAGMA.eval_continuous(i as f64 / 10.0);
            format!("#{:02x}{:02x}{:02x}", c.r, c.g, c.b)
        })
        .collect();
    format!(
        r#"<div class="small" style="display:flex;align-items:center;gap:6px">FLIP 0<span style="display:inline-block;width:240px;height:12px;background:linear-gradient(to right,{})"></span>1 (magma, as FLIP draws it)</div>"#,
        stops.join(",")
    )
}

fn img(path: &Path) -> String {
    format!(r#"<img src="{}">"#, escape(&path.display().to_string()))
}

fn row(p: &PerceptualStudy, c: &Comparison, answer: Option<&Answer>, direct: Option<&Comparison>) -> String {
    let mut h = String::new();
    let floor = |l: Lighting| {
        let (m, q) = floor_of(p, l);
        format!("<td>{m:.4} / {q:.4}</td>")
    };
    let mark = |c: &Comparison| if p.above_floor(c) { "" } else { " ≤ floor" };
    let _ = write!(
        h,
        "<tr><td>{}</td><td class=\"l\">{}</td>{}{}{}<td class=\"l\">{}</td>",
        escape(c.model.label()),
        escape(if c.reference == Configuration::Lambert { "Lambert" } else { c.reference.label() }),
        flip_cell(c.flip.mean.value),
        flip_cell(c.flip.p95.value),
        floor(Lighting::Global),
        mark(c)
    );
    match direct {
        Some(d) if !p.direct_only => {
            let _ = write!(
                h,
                "{}{}{}<td class=\"l\">{}</td>",
                flip_cell(d.flip.mean.value),
                flip_cell(d.flip.p95.value),
                floor(Lighting::Direct),
                mark(d)
            );
        }
        _ => h.push_str(r#"<td colspan="4">(direct only)</td>"#),
    }
    match answer {
        Some(a) => {
            let _ = write!(
                h,
                "<td>{:+.4} ± {:.4}</td><td class=\"l\">{}</td><td>{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td>",
                a.delta.value,
                a.delta.half_width,
                a.visibility.name(),
                answers::pct(a.energy),
                a.energy_verdict.name(),
                a.agreement.name()
            );
        }
        None => h.push_str(r#"<td colspan="5"></td>"#),
    }
    h.push_str("</tr>");
    h
}

/// The section: what is measured, then per scene the strips, the table and the answers.
pub fn html(studies: &[PerceptualStudy], scenes: &[SceneStudy], truths: &[TruthStudy], notes: &[String]) -> String {
    let mut h = String::new();
    h.push_str(r#"<div class="scene"><h2>Is the difference visible? Perceptual difference (HDR-FLIP)</h2>"#);
    let _ = write!(
        h,
        "<p>{}. A value is above the noise floor when its interval lies entirely above the floor's (“≤ floor” marks the others). \
ΔFLIP = mean FLIP<sub>global</sub> − mean FLIP<sub>direct</sub> (paired per left-out pass): the difference is <i>more visible</i> \
under global illumination when its interval lies above 0, <i>less visible</i> below 0, <i>undecided</i> when it contains 0, \
<i>within the noise</i> when a lighting's value is not above its floor. The energy verdict is on Δ of the luminance ratios \
(grows / shrinks / undecided).</p>",
        escape(METRIC)
    );
    h.push_str(&colour_bar());
    for n in notes {
        let _ = write!(h, r#"<p class="note">{}</p>"#, escape(n));
    }
    for p in studies {
        let _ = write!(h, "<h3>{}</h3>", escape(&p.scene_name));
        let scene = scenes.iter().find(|s| s.name == p.scene_name);
        for (l, against_lambert, against_surface) in &p.strips {
            let heading =
                if p.direct_only { "global = direct lighting".to_string() } else { format!("{} lighting", l.name()) };
            let _ = write!(h, "<h4>{heading}</h4>");
            if let Some((_, _, diff)) = scene.and_then(|s| s.strips.iter().find(|(x, _, _)| x == l)) {
                let range =
                    scene.and_then(|s| s.difference_ranges.iter().find(|(x, _)| x == l)).map_or(f32::NAN, |r| r.1);
                let _ = write!(
                    h,
                    r#"<p class="small">Signed heatmap (model − Lambert) / Lambert, blue −{:.0} % … red +{:.0} %:</p>{}"#,
                    range * 100.0,
                    range * 100.0,
                    img(diff)
                );
            }
            let _ = write!(
                h,
                r#"<p class="small">HDR-FLIP against Lambert (first tile: the noise floor, Lambert with other seeds):</p>{}"#,
                img(against_lambert)
            );
            if let Some(s) = against_surface {
                let truth = truths.iter().find(|t| t.scene_name == p.scene_name);
                if let Some((_, diff, range)) = truth.and_then(|t| t.strips.iter().find(|(x, _, _)| x == l)) {
                    let _ = write!(
                        h,
                        r#"<p class="small">Signed heatmap (model − surface) / surface, blue −{:.0} % … red +{:.0} %:</p>{}"#,
                        range * 100.0,
                        range * 100.0,
                        img(diff)
                    );
                }
                let _ = write!(h, r#"<p class="small">HDR-FLIP against each model's own surface:</p>{}"#, img(s));
            }
            h.push_str(&colour_bar());
        }
        if let Some(e) = p.exposure(Lighting::Global) {
            let _ = write!(
                h,
                r#"<p class="small">Exposure range (global): {:.2} … {:.2} stops, {} exposures; (direct): {}.</p>"#,
                e.start,
                e.stop,
                e.count,
                p.exposure(Lighting::Direct)
                    .map(|d| format!("{:.2} … {:.2} stops, {} exposures", d.start, d.stop, d.count))
                    .unwrap_or_default()
            );
        }
        h.push_str("<table><tr><th>model</th><th>against</th><th>mean, global</th><th>p95, global</th><th>floor mean / p95</th><th></th><th>mean, direct</th><th>p95, direct</th><th>floor mean / p95</th><th></th><th>ΔFLIP</th><th>perceptual</th><th>energy Δ</th><th>energy</th><th>agreement</th></tr>");
        for c in p.comparisons.iter().filter(|c| c.lighting == Lighting::Global) {
            let d = p.comparison(c.model, c.reference, Lighting::Direct);
            let a = p.answers.iter().find(|a| a.model == c.model && a.reference == c.reference);
            h.push_str(&row(p, c, a, d));
        }
        h.push_str("</table><ul>");
        for a in answers::perceptual_scene_answers(p) {
            let _ = write!(h, "<li>{}</li>", escape(&a));
        }
        h.push_str("</ul>");
    }
    h.push_str("</div>");
    h
}
