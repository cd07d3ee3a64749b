//! The model variants' section per scene ([`crate::study::variants`]): what each variant
//! means, its strips and heatmaps, and its ratio to Lambert in both lightings.

use super::{RegionJson, StripJson, ratio_cell, strips_html};
use crate::markup::escape;
use crate::study::configuration::{Configuration, VARIANTS};
use crate::study::variants::{VariantResult, VariantStudy};
use crate::study::{Lighting, answers};
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write as _;
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

pub fn html(v: &VariantStudy) -> String {
    let mut h = String::new();
    let name = escape(&v.scene_name);
    let _ = write!(
        h,
        r#"<div class="scene"><h2>{name}: model variants</h2><p>Wolff's constant K and the Oren–Nayar model, each set as a property in a derived copy of the scene
(<code>{name}/variants/*.xml</code>). The defaults are the main run's images. The other variants use the main run's seeds and budget, so their ratio to Lambert is paired with the same Lambert passes.
n = 1.4, F = Fresnel reflectance, F<sub>dr</sub> = its cosine-weighted hemispherical average (docs/models.md: Wolff normalisations, Oren-Nayar qualitative and full).</p><ul>"#
    );
    for x in VARIANTS {
        let property = x.property().map(|(k, val)| format!(" (<code>{}={}</code>)", escape(k), escape(val)));
        let default = if x.is_main_run() { ", the default" } else { "" };
        let _ = write!(
            h,
            "<li><b>{}</b>{}{default}: {}</li>",
            escape(x.label()),
            property.unwrap_or_default(),
            escape(x.meaning())
        );
    }
    h.push_str("</ul>");
    for (l, strip, diff, range) in &v.strips {
        h.push_str(&strips_html(*l, strip, diff, *range, "variant"));
    }
    h.push_str("<table><tr><th>variant</th><th>ratio, global</th><th>ratio, direct</th><th>Δ</th><th>source</th></tr>");
    for (x, g, d) in both_lightings(v) {
        let _ = write!(
            h,
            "<tr><td>{}</td>{}{}<td>{:+.4}</td>",
            escape(x.label()),
            ratio_cell(g.ratio),
            ratio_cell(d.ratio),
            (g.ratio.value - 1.0).abs() - (d.ratio.value - 1.0).abs()
        );
        match &g.scene_file {
            Some(f) => {
                let _ = write!(
                    h,
                    r#"<td class="l"><a href="{}">derived scene</a></td></tr>"#,
                    escape(&f.display().to_string())
                );
            }
            None => h.push_str(r#"<td class="l">main run</td></tr>"#),
        }
    }
    h.push_str("</table>");
    let names: Vec<String> =
        v.results.first().map(|r| r.regions.iter().map(|x| x.name.clone()).collect()).unwrap_or_default();
    for (i, region) in names.iter().enumerate() {
        let _ = write!(
            h,
            "<h4>Region: {}</h4><table><tr><th>variant</th><th>ratio, global</th><th>ratio, direct</th></tr>",
            escape(region)
        );
        for (x, g, d) in both_lightings(v) {
            let (Some(gr), Some(dr)) = (g.regions.get(i), d.regions.get(i)) else { continue };
            let _ =
                write!(h, "<tr><td>{}</td>{}{}</tr>", escape(x.label()), ratio_cell(gr.ratio), ratio_cell(dr.ratio));
        }
        h.push_str("</table>");
    }
    h.push_str("</div>");
    h
}
