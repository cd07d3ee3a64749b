//! The perceptual section ([`crate::study::perceptual`]): per scene and lighting, the FLIP
//! maps beside the signed heatmaps (with the colour bar), a table of the mean and the 95th
//! percentile of HDR-FLIP with their 99 % jackknife intervals and the noise floor, and the
//! verdicts (more or less visible under global illumination, against the energy verdict).

use crate::study::answers;
use crate::study::configuration::Configuration;
use crate::study::main_run::SceneStudy;
use crate::study::options::{Lighting, StudyOptions};
use crate::study::perceptual::{self, Answer, Comparison, Exposure, FlipPair, PerceptualStudy};
use crate::study::ratio::Ratio;
use crate::study::section::{JsonObject, Progress, Scene, Section, Study};
use crate::study::truth::TruthStudy;
use askama::Template;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The perceptual differences as a section of the study (unless `--no-perceptual`). A scene
/// whose HDR-FLIP evaluation fails gets a note, and the study goes on.
pub struct Perceptual;

impl Section for Perceptual {
    fn name(&self) -> &'static str {
        "perceptual differences"
    }

    fn passes(&self, _scene: &Scene, opts: &StudyOptions) -> u64 {
        perceptual::pass_count(opts)
    }

    fn run(&self, scene: &Scene, study: &mut Study, progress: &dyn Progress) -> Result<(), String> {
        let opts = &study.options;
        if !opts.perceptual {
            return Ok(());
        }
        for l in [Lighting::Global, Lighting::Direct] {
            let what = format!("{} {} Lambert, other seeds", scene.name, l.name());
            perceptual::render_floor(&scene.path, &scene.name, l, &scene.regions, opts, &|_: u32| {
                progress.pass(&what)
            })?;
        }
        progress.step(&format!("{} HDR-FLIP", scene.name));
        let truths = study.truths.iter().find(|t| t.scene_name == scene.name);
        match perceptual::run(study.scene(&scene.name)?, truths, opts) {
            Ok(p) => study.perceptual.push(p),
            Err(e) => study
                .perceptual_notes
                .push(format!("{}: the perceptual differences were not computed: {e}", scene.name)),
        }
        Ok(())
    }

    fn answers(&self, study: &Study) -> Vec<String> {
        let mut out = answers::perceptual_summary(&study.perceptual);
        out.extend(study.perceptual.iter().flat_map(answers::perceptual_scene_answers));
        out.extend(answers::perceptual_closing(&study.perceptual));
        out
    }

    fn json(&self, study: &Study, out: &mut JsonObject) -> Result<(), String> {
        out.entry("perceptual", &json(&study.perceptual, &study.perceptual_notes))
    }

    fn html(&self, study: &Study, _out: &Path) -> Result<String, String> {
        if study.perceptual.is_empty() && study.perceptual_notes.is_empty() {
            return Ok(String::new());
        }
        html(&study.perceptual, &study.scenes, &study.truths, &study.perceptual_notes).map_err(|e| e.to_string())
    }
}

/// The perceptual differences in study.json.
#[derive(Serialize)]
pub struct PerceptualJson {
    /// The metric and how every value is computed.
    pub metric: &'static str,
    pub scenes: Vec<SceneJson>,
    /// Scenes without perceptual values, and why.
    pub notes: Vec<String>,
}

/// One scene's perceptual differences.
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

/// HDR-FLIP's exposure range of one lighting.
#[derive(Serialize)]
pub struct ExposureJson {
    pub lighting: &'static str,
    #[serde(flatten)]
    pub exposure: Exposure,
}

/// The noise floor of one lighting.
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

/// The FLIP strips of one lighting.
#[derive(Serialize)]
pub struct StripJson {
    pub lighting: &'static str,
    /// FLIP maps against Lambert (the noise floor's first).
    pub flip_against_lambert: PathBuf,
    /// FLIP maps of the rough models against their surfaces.
    pub flip_against_surface: Option<PathBuf>,
}

/// One pair (a model against Lambert or its surface) in one lighting.
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

/// The verdicts of one pair: ΔFLIP and the energy Δ.
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

/// What the values are and how they are computed, for study.json and the report.
pub const METRIC: &str = "HDR-FLIP (flip-evaluator, NVIDIA's reference implementation) of the two mean images of a pair; one exposure range per scene and lighting, derived by HDR-FLIP from that lighting's Lambert image (ACES tone mapping, 67 pixels per degree); intervals: 99 % jackknife over the passes (pass k left out of both images); noise floor: Lambert against Lambert rendered with other seeds at the same budget";

fn floor_of(p: &PerceptualStudy, l: Lighting) -> (f64, f64) {
    p.floor(l).map_or((f64::NAN, f64::NAN), |f| (f.mean.value.value, f.p95.value.value))
}

/// The perceptual differences in study.json.
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

/// The perceptual section of report.html.
#[derive(Template)]
#[template(path = "perceptual.html")]
struct PerceptualHtml<'a> {
    metric: &'static str,
    /// The colour stops of FLIP's magma, for a CSS gradient.
    magma: String,
    notes: &'a [String],
    scenes: Vec<SceneHtml<'a>>,
}

struct SceneHtml<'a> {
    name: &'a str,
    lightings: Vec<LightingHtml<'a>>,
    exposure: Option<String>,
    floor_global: (f64, f64),
    floor_direct: (f64, f64),
    rows: Vec<Row<'a>>,
    answers: Vec<String>,
}

/// One lighting's strips: the signed heatmaps (with their range) beside the FLIP maps.
struct LightingHtml<'a> {
    heading: String,
    against_lambert_signed: Option<(&'a Path, f32)>,
    against_lambert: &'a Path,
    against_surface_signed: Option<(&'a Path, f32)>,
    against_surface: Option<&'a Path>,
}

/// One pair in both lightings (no direct one when the scene is direct only), with its answer.
struct Row<'a> {
    reference: &'static str,
    global: &'a Comparison,
    global_above: bool,
    direct: Option<&'a Comparison>,
    direct_above: bool,
    answer: Option<&'a Answer>,
}

/// A luminance-ratio change in percent with its interval.
fn pct(r: &Ratio) -> String {
    answers::pct(*r)
}

fn scene_html<'a>(
    p: &'a PerceptualStudy,
    scene: Option<&'a SceneStudy>,
    truth: Option<&'a TruthStudy>,
) -> SceneHtml<'a> {
    let lightings = p
        .strips
        .iter()
        .map(|(l, against_lambert, against_surface)| LightingHtml {
            heading: if p.direct_only { "global = direct lighting".into() } else { format!("{} lighting", l.name()) },
            against_lambert_signed: scene.and_then(|s| {
                let (_, _, diff) = s.strips.iter().find(|(x, _, _)| x == l)?;
                Some((diff.as_path(), s.difference_range(*l)))
            }),
            against_lambert,
            against_surface_signed: against_surface.as_ref().and(truth).and_then(|t| {
                let (_, diff, range) = t.strips.iter().find(|(x, _, _)| x == l)?;
                Some((diff.as_path(), *range))
            }),
            against_surface: against_surface.as_deref(),
        })
        .collect();
    let exposure = |e: &Exposure| format!("{:.2} … {:.2} stops, {} exposures", e.start, e.stop, e.count);
    let rows = p
        .comparisons
        .iter()
        .filter(|c| c.lighting == Lighting::Global)
        .map(|c| {
            let direct = p.comparison(c.model, c.reference, Lighting::Direct).filter(|_| !p.direct_only);
            Row {
                reference: if c.reference == Configuration::Lambert { "Lambert" } else { c.reference.label() },
                global: c,
                global_above: p.above_floor(c),
                direct,
                direct_above: direct.is_some_and(|d| p.above_floor(d)),
                answer: p.answers.iter().find(|a| a.model == c.model && a.reference == c.reference),
            }
        })
        .collect();
    SceneHtml {
        name: &p.scene_name,
        lightings,
        exposure: p.exposure(Lighting::Global).map(|e| {
            format!("{}; (direct): {}", exposure(e), p.exposure(Lighting::Direct).map(exposure).unwrap_or_default())
        }),
        floor_global: floor_of(p, Lighting::Global),
        floor_direct: floor_of(p, Lighting::Direct),
        rows,
        answers: answers::perceptual_scene_answers(p),
    }
}

/// The section: what is measured, then per scene the strips, the table and the answers.
pub fn html(
    studies: &[PerceptualStudy],
    scenes: &[SceneStudy],
    truths: &[TruthStudy],
    notes: &[String],
) -> askama::Result<String> {
    let magma: Vec<String> = (0..=10)
        .map(|i| {
            let c = colorous::MAGMA.eval_continuous(i as f64 / 10.0);
            format!("#{:02x}{:02x}{:02x}", c.r, c.g, c.b)
        })
        .collect();
    PerceptualHtml {
        metric: METRIC,
        magma: magma.join(","),
        notes,
        scenes: studies
            .iter()
            .map(|p| {
                let scene = scenes.iter().find(|s| s.name == p.scene_name);
                scene_html(p, scene, truths.iter().find(|t| t.scene_name == p.scene_name))
            })
            .collect(),
    }
    .render()
}
