//! The model variants' section per scene ([`crate::study::variants`]): what each variant
//! means, its strips and heatmaps, and its ratio to Lambert in both lightings.

use super::shared::{LightingRatios, RegionJson, StripJson};
use crate::study::answers;
use crate::study::configuration::{Configuration, VARIANTS};
use crate::study::options::{Lighting, StudyOptions};
use crate::study::section::{JsonObject, Progress, Scene, Section, Study};
use crate::study::variants::{self, VariantResult, VariantStudy};
use askama::Template;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The model variants as a section of the study, for the scenes of `--variant-scenes`.
pub struct Variants;

impl Section for Variants {
    fn name(&self) -> &'static str {
        "variants"
    }

    fn passes(&self, scene: &Scene, opts: &StudyOptions) -> u64 {
        if opts.variants_for(&scene.name) { variants::pass_count(opts.passes) } else { 0 }
    }

    fn run(&self, scene: &Scene, study: &mut Study, progress: &dyn Progress) -> Result<(), String> {
        if !study.options.variants_for(&scene.name) {
            return Ok(());
        }
        let v = variants::run(study.scene(&scene.name)?, &study.options, &|what: &str, _: u32| progress.pass(what))?;
        study.variants.push(v);
        Ok(())
    }

    fn answers(&self, study: &Study) -> Vec<String> {
        study.variants.iter().flat_map(answers::variant_answers).collect()
    }

    fn json(&self, study: &Study, out: &mut JsonObject) -> Result<(), String> {
        out.entry("variants", &study.variants.iter().map(json).collect::<Vec<_>>())
    }

    fn html(&self, study: &Study, _out: &Path) -> Result<String, String> {
        study.variants.iter().map(|v| html(v).map_err(|e| e.to_string())).collect()
    }
}

/// One scene's variants in study.json.
#[derive(Serialize)]
pub struct VariantsJson {
    pub scene: String,
    pub strips: Vec<StripJson>,
    pub variants: Vec<VariantJson>,
    pub answers: Vec<String>,
}

/// One variant in both lightings.
#[derive(Serialize)]
pub struct VariantJson {
    pub key: &'static str,
    pub bsdf: &'static str,
    pub label: &'static str,
    /// The `<bsdf>` property that selects the variant.
    pub property: BTreeMap<&'static str, &'static str>,
    /// The plugin's default: the main run's images.
    pub main_run: bool,
    pub meaning: &'static str,
    /// The derived scene (none for the main run's images).
    pub scene_file: Option<PathBuf>,
    /// Its luminance ratio to Lambert.
    #[serde(flatten)]
    pub ratios: LightingRatios,
    pub seconds_global: Option<f64>,
    pub seconds_direct: Option<f64>,
    pub exr_global: PathBuf,
    pub exr_direct: PathBuf,
    pub regions: Vec<RegionJson>,
}

/// Each variant with its global and direct results, in the table's order.
fn both_lightings(v: &VariantStudy) -> impl Iterator<Item = (Configuration, &VariantResult, &VariantResult)> {
    VARIANTS.into_iter().filter_map(|x| Some((x, v.result(x, Lighting::Global)?, v.result(x, Lighting::Direct)?)))
}

/// The scene's variants in study.json.
pub fn json(v: &VariantStudy) -> VariantsJson {
    VariantsJson {
        scene: v.scene_name.clone(),
        strips: v
            .strips
            .iter()
            .map(|(l, strip, diff, range)| StripJson {
                lighting: l.name(),
                strip: strip.clone(),
                difference: diff.clone(),
                difference_range: *range,
            })
            .collect(),
        variants: both_lightings(v)
            .map(|(x, g, d)| VariantJson {
                key: x.key(),
                bsdf: x.bsdf(),
                label: x.label(),
                property: x.property().into_iter().collect(),
                main_run: x.is_main_run(),
                meaning: x.meaning(),
                scene_file: g.scene_file.clone(),
                ratios: LightingRatios::new(g.ratio, d.ratio),
                seconds_global: g.seconds,
                seconds_direct: d.seconds,
                exr_global: g.exr.clone(),
                exr_direct: d.exr.clone(),
                regions: RegionJson::pair(&g.regions, &d.regions),
            })
            .collect(),
        answers: answers::variant_answers(v),
    }
}

/// The variants' section of report.html.
#[derive(Template)]
#[template(path = "variants.html")]
struct VariantsHtml<'a> {
    v: &'a VariantStudy,
    variants: [Configuration; VARIANTS.len()],
    rows: Vec<(Configuration, &'a VariantResult, &'a VariantResult)>,
    regions: Vec<&'a str>,
}

/// The scene's variants in report.html.
pub fn html(v: &VariantStudy) -> askama::Result<String> {
    let regions = v.results.first().map(|r| r.regions.iter().map(|x| x.name.as_str()).collect()).unwrap_or_default();
    VariantsHtml { v, variants: VARIANTS, rows: both_lightings(v).collect(), regions }.render()
}
