//! The table report.html opens with: per scene and model (the main run's, against Lambert),
//! the answer to the paper's question as the sections measured it. The energy answer: the
//! ratio to Lambert in both lightings, Δ = |ratio_global − 1| − |ratio_direct − 1| with its
//! 99 % interval ([`SceneStudy::growth`]) and its verdict; when the perceptual step ran, the
//! mean HDR-FLIP in both lightings, ΔFLIP, its verdict and how the two answers relate (the
//! perceptual answers, [`crate::study::perceptual::Answer`]).

use crate::study::answers::{ci, flip_ci, pct};
use crate::study::configuration::{Configuration, main_run};
use crate::study::main_run::SceneStudy;
use crate::study::options::Lighting;
use crate::study::ratio::Verdict;
use crate::study::section::Study;
use askama::Template;

/// One scene and model.
struct Row {
    scene: String,
    model: &'static str,
    ratio_global: String,
    ratio_direct: String,
    delta: String,
    verdict: &'static str,
    /// Mean FLIP global and direct, ΔFLIP, its verdict, the agreement with the energy answer
    /// (when the perceptual step ran; dashes for a scene without its values).
    flip: Option<[String; 5]>,
}

/// The answer table.
#[derive(Template)]
#[template(path = "answer_table.html")]
struct AnswerTable {
    /// Whether the perceptual columns are shown.
    perceptual: bool,
    rows: Vec<Row>,
}

fn row(study: &Study, s: &SceneStudy, m: Configuration, perceptual: bool) -> Option<Row> {
    let g = s.result(m, Lighting::Global)?.ratio;
    let d = s.result(m, Lighting::Direct)?.ratio;
    let delta = s.growth(m)?;
    let flip = perceptual.then(|| {
        let lambert = Configuration::Lambert;
        let p = study.perceptual.iter().find(|p| p.scene_name == s.name);
        let mean = |l: Lighting| {
            p.and_then(|p| p.comparison(m, lambert, l)).map_or("–".to_string(), |c| flip_ci(c.flip.mean.value))
        };
        match p.and_then(|p| p.answers.iter().find(|a| a.model == m && a.reference == lambert)) {
            Some(a) => [
                mean(Lighting::Global),
                mean(Lighting::Direct),
                flip_ci(a.delta),
                a.visibility.name().to_string(),
                a.agreement.name().to_string(),
            ],
            None => [mean(Lighting::Global), mean(Lighting::Direct), "–".into(), "–".into(), "–".into()],
        }
    });
    Some(Row {
        scene: s.name.clone(),
        model: m.label(),
        ratio_global: ci(g),
        ratio_direct: ci(d),
        delta: pct(delta),
        verdict: Verdict::of(delta, s.direct_only()).name(),
        flip,
    })
}

/// The table's HTML: a row per scene and model of the main run (Lambert, the reference, has
/// none).
pub fn html(study: &Study) -> askama::Result<String> {
    let perceptual = !study.perceptual.is_empty();
    let rows = study
        .scenes
        .iter()
        .flat_map(|s| main_run().into_iter().skip(1).filter_map(move |m| row(study, s, m, perceptual)))
        .collect();
    AnswerTable { perceptual, rows }.render()
}
