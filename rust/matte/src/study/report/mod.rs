//! The study's sections, in order ([`SECTIONS`]), and what is written from them: study.json
//! (the run's renderer, passes and spp, the answers, then each section's entries) and
//! report.html (the answer table, [`answer_table`], and the answer sentences, then each
//! section's part). Each section is one file with its run, its JSON and its HTML (askama
//! templates in `templates/`): the main run per scene ([`scenes`]), the model variants
//! ([`variants_section`]), the models against their true surfaces ([`truth_section`], also
//! written alone as truth.json), the perceptual differences ([`perceptual_section`]) and the
//! convergence series ([`convergence_section`], with its plot in [`plot`]).

pub mod answer_table;
pub mod convergence_section;
pub mod perceptual_section;
pub mod plot;
pub mod scenes;
pub mod shared;
pub mod truth_section;
pub mod variants_section;

use crate::study::section::{JsonObject, Section, Study};
use askama::Template;
use serde::Serializer;
use serde::ser::SerializeMap;

/// The study's sections: the order they run in on each scene, of study.json and of the report.
pub const SECTIONS: &[&dyn Section] = &[
    &scenes::MainRun,
    &variants_section::Variants,
    &truth_section::Truths,
    &perceptual_section::Perceptual,
    &convergence_section::Convergence,
];

/// Every section's answer sentences, in the sections' order.
pub fn answers(study: &Study) -> Vec<String> {
    SECTIONS.iter().flat_map(|s| s.answers(study)).collect()
}

/// A JSON object with the run's renderer, passes and spp, the answers when `with_answers`,
/// and the entries of `sections`.
fn json_of(study: &Study, sections: &[&dyn Section], with_answers: bool) -> Result<String, String> {
    let mut ser = serde_json::Serializer::pretty(Vec::new());
    let mut map = (&mut ser).serialize_map(None).map_err(|e| e.to_string())?;
    let mut out = JsonObject::new(&mut map);
    out.entry("renderer", &study.renderer)?;
    out.entry("passes", &study.options.passes)?;
    out.entry("spp", &study.options.spp)?;
    if with_answers {
        out.entry("answers", &answers(study))?;
    }
    for s in sections {
        s.json(study, &mut out).map_err(|e| format!("{}: {e}", s.name()))?;
    }
    map.end().map_err(|e| e.to_string())?;
    String::from_utf8(ser.into_inner()).map_err(|e| e.to_string())
}

/// study.json.
pub fn json(study: &Study) -> Result<String, String> {
    json_of(study, SECTIONS, true)
}

/// report.html: the answer table and sentences, then the sections in order.
#[derive(Template)]
#[template(path = "study_report.html")]
struct ReportHtml<'a> {
    renderer: &'a str,
    passes: u32,
    spp: u32,
    /// The answer table.
    table: String,
    answers: Vec<String>,
    /// The sections, rendered by their own templates.
    sections: Vec<String>,
}

/// report.html, for the folder `out` (the sections put the files they show there).
pub fn html(study: &Study, out: &std::path::Path) -> Result<String, String> {
    let mut sections = Vec::new();
    for s in SECTIONS {
        let part = s.html(study, out).map_err(|e| format!("{}: {e}", s.name()))?;
        if !part.is_empty() {
            sections.push(part);
        }
    }
    ReportHtml {
        renderer: &study.renderer,
        passes: study.options.passes,
        spp: study.options.spp,
        table: answer_table::html(study).map_err(|e| format!("answer table: {e}"))?,
        answers: answers(study),
        sections,
    }
    .render()
    .map_err(|e| e.to_string())
}

/// study.json, the sections' own JSON files and report.html in the study's output folder.
pub fn write(study: &Study) -> Result<(), String> {
    let out = &study.options.out;
    let write = |name: &str, text: String| {
        let path = out.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))
    };
    write("study.json", json(study)?)?;
    for s in SECTIONS {
        if let Some(file) = s.json_file() {
            write(file, json_of(study, &[*s], false)?)?;
        }
    }
    write("report.html", html(study, out).map_err(|e| format!("report.html: {e}"))?)
}
