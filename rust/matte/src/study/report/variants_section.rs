//! The model variants' section per scene ([`crate::study::variants`]): what each variant
//! means, its strips and heatmaps, and its ratio to Lambert in both lightings.

use super::{RegionJson, StripJson};
use crate::study::configuration::{Configuration, VARIANTS};
use crate::study::variants::{VariantResult, VariantStudy};
use crate::study::{Lighting, answers};
use askama::Template;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;

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
    pub ratio_global: f64,
    pub ratio_global_ci99: f64,
    pub ratio_direct: f64,
    pub ratio_direct_ci99: f64,
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
                ratio_global: g.ratio.value,
                ratio_global_ci99: g.ratio.half_width,
                ratio_direct: d.ratio.value,
                ratio_direct_ci99: d.ratio.half_width,
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

pub fn html(v: &VariantStudy) -> askama::Result<String> {
    let regions = v.results.first().map(|r| r.regions.iter().map(|x| x.name.as_str()).collect()).unwrap_or_default();
    VariantsHtml { v, variants: VARIANTS, rows: both_lightings(v).collect(), regions }.render()
}
