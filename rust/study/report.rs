//! `study.json` and `report.html`: per scene the strips and heatmaps, and per model the
//! luminance ratio to Lambert (99 % CI) under global and direct lighting, the change between
//! them (the paper's question), and the edge/flat concentration of the difference; then the
//! model variants and the convergence series ([`super::report_extra`]).

use super::{Lighting, SceneStudy, Study, report_extra};
use serde_json::json;
use std::fmt::Write as _;
use std::path::Path;

fn find<'a>(s: &'a SceneStudy, bsdf: &str, l: Lighting) -> Option<&'a super::ModelResult> {
    s.results.iter().find(|r| r.model.bsdf == bsdf && r.lighting == l)
}

/// Per named region: the ratio to Lambert and its 99 % half-width in both lightings.
pub(super) fn regions_json(global: &[(String, f64, f64)], direct: &[(String, f64, f64)]) -> Vec<serde_json::Value> {
    global
        .iter()
        .zip(direct)
        .map(|((n, gm, gh), (_, dm, dh))| json!({"name": n, "ratio_global": gm, "ratio_global_ci99": gh, "ratio_direct": dm, "ratio_direct_ci99": dh}))
        .collect()
}

/// One lighting's strip and heatmap strip with the heatmap's colour scale (`what` − Lambert).
pub(super) fn strips_html(l: Lighting, strip: &Path, diff: &Path, range: f32, what: &str) -> String {
    format!(
        r#"<h3>{} lighting</h3><img src="{}"><br><img src="{}"><p>Heatmap: ({what} − Lambert) / Lambert, blue −{:.0} % … red +{:.0} %.</p>"#,
        l.name(),
        strip.display(),
        diff.display(),
        range * 100.0,
        range * 100.0
    )
}

pub fn json(study: &Study) -> serde_json::Value {
    let studies = &study.scenes;
    let scenes: Vec<_> = studies
        .iter()
        .map(|s| {
            let models: Vec<_> = super::MODELS
                .iter()
                .filter_map(|m| {
                    let g = find(s, m.bsdf, Lighting::Global)?;
                    let d = find(s, m.bsdf, Lighting::Direct)?;
                    Some(json!({
                        "model": m.bsdf,
                        "ratio_global": g.ratio.0, "ratio_global_ci99": g.ratio.1,
                        "ratio_direct": d.ratio.0, "ratio_direct_ci99": d.ratio.1,
                        "abs_difference_global_minus_direct": (g.ratio.0 - 1.0).abs() - (d.ratio.0 - 1.0).abs(),
                        "edge_mean_abs_rel_diff_global": g.edge_flat.0, "flat_mean_abs_rel_diff_global": g.edge_flat.1,
                        "edge_mean_abs_rel_diff_direct": d.edge_flat.0, "flat_mean_abs_rel_diff_direct": d.edge_flat.1,
                        "seconds_global": g.seconds, "seconds_direct": d.seconds,
                        "exr_global": g.exr, "exr_direct": d.exr,
                        "regions": regions_json(&g.regions, &d.regions),
                    }))
                })
                .collect();
            json!({
                "scene": s.scene.display().to_string(),
                "strips": s.strips.iter().map(|(l, a, b)| json!({"lighting": l.name(), "strip": a, "difference": b})).collect::<Vec<_>>(),
                "models": models,
            })
        })
        .collect();
    json!({
        "renderer": study.renderer, "passes": study.passes, "spp": study.spp,
        "answers": super::answers::answers(study),
        "scenes": scenes,
        "variants": study.variants.iter().map(report_extra::variants_json).collect::<Vec<_>>(),
        "convergence": study.convergence.iter().map(report_extra::convergence_json).collect::<Vec<_>>(),
    })
}

pub fn html(study: &Study) -> String {
    let (studies, renderer, passes, spp) = (&study.scenes, &study.renderer, study.passes, study.spp);
    let mut h = String::new();
    let _ = write!(
        h,
        r#"<!doctype html><html><head><meta charset="utf-8"><title>matte study</title><style>
body{{font-family:system-ui,sans-serif;margin:24px;color:#222;max-width:1400px}} img{{max-width:100%;border:1px solid #ddd}}
table{{border-collapse:collapse;font-size:14px;margin:8px 0}} td,th{{padding:3px 10px;border-bottom:1px solid #eee;text-align:right}} td{{white-space:nowrap}}
th:first-child,td:first-child{{text-align:left}} .scene{{border-top:1px solid #ccc;padding-top:12px;margin-top:16px}}
.note{{background:#fff4d6;border-left:4px solid #e0a800;padding:6px 10px}} td.l{{text-align:left}} .small{{font-size:13px;color:#555}}
</style></head><body><h1>matte study: diffuse models under global illumination</h1>
<p>Renderer: {renderer}; {passes} passes, {spp} spp per image in total; every model uses the same seeds (paired passes).
Ratio = image-mean luminance of the model / Lambert, ± 99 % confidence interval from the paired per-pass ratios.
"Global" is the scene's path depth, "direct" is max_depth 2. Δ = |ratio<sub>global</sub> − 1| − |ratio<sub>direct</sub> − 1|:
positive = the difference to Lambert grows under global illumination. Edge/flat = mean |relative luminance difference| to
Lambert on the 10 % of pixels with the strongest gradient of Lambert's image vs on the others.</p>"#
    );
    h.push_str("<h2>Answers, computed from the measurements below</h2><ul>");
    for a in super::answers::answers(study) {
        let _ = write!(h, "<li>{}</li>", report_extra::esc(&a));
    }
    h.push_str("</ul>");
    for s in studies {
        let _ = write!(h, r#"<div class="scene"><h2>{}</h2>"#, s.name);
        for (l, strip, diff) in &s.strips {
            let range = s.difference_ranges.iter().find(|(x, _)| x == l).map_or(f32::NAN, |r| r.1);
            h.push_str(&strips_html(*l, strip, diff, range, "model"));
        }
        h.push_str("<table><tr><th>model</th><th>ratio, global</th><th>ratio, direct</th><th>Δ</th><th>edge / flat, global</th><th>edge / flat, direct</th></tr>");
        for m in super::MODELS {
            let (Some(g), Some(d)) = (find(s, m.bsdf, Lighting::Global), find(s, m.bsdf, Lighting::Direct)) else {
                continue;
            };
            let _ = write!(
                h,
                "<tr><td>{}</td><td>{:.4} ± {:.4}</td><td>{:.4} ± {:.4}</td><td>{:+.4}</td><td>{:.3} / {:.3}</td><td>{:.3} / {:.3}</td></tr>",
                m.label,
                g.ratio.0,
                g.ratio.1,
                d.ratio.0,
                d.ratio.1,
                (g.ratio.0 - 1.0).abs() - (d.ratio.0 - 1.0).abs(),
                g.edge_flat.0,
                g.edge_flat.1,
                d.edge_flat.0,
                d.edge_flat.1
            );
        }
        h.push_str("</table>");
        let names: Vec<String> =
            s.results.first().map(|r| r.regions.iter().map(|x| x.0.clone()).collect()).unwrap_or_default();
        for (i, name) in names.iter().enumerate() {
            let _ = write!(
                h,
                "<h4>Region: {name}</h4><table><tr><th>model</th><th>ratio, global</th><th>ratio, direct</th></tr>"
            );
            for m in super::MODELS {
                let (Some(g), Some(d)) = (find(s, m.bsdf, Lighting::Global), find(s, m.bsdf, Lighting::Direct)) else {
                    continue;
                };
                let _ = write!(
                    h,
                    "<tr><td>{}</td><td>{:.4} ± {:.4}</td><td>{:.4} ± {:.4}</td></tr>",
                    m.label, g.regions[i].1, g.regions[i].2, d.regions[i].1, d.regions[i].2
                );
            }
            h.push_str("</table>");
        }
        h.push_str("</div>");
    }
    for v in &study.variants {
        h.push_str(&report_extra::variants_html(v));
    }
    for s in &study.convergence {
        h.push_str(&report_extra::convergence_html(s, study.variants.iter().find(|v| v.scene_name == s.scene_name)));
    }
    h.push_str("</body></html>\n");
    h
}

pub fn write(out: &Path, study: &Study) -> Result<(), String> {
    let j = serde_json::to_string_pretty(&json(study)).expect("json");
    std::fs::write(out.join("study.json"), j).map_err(|e| e.to_string())?;
    std::fs::write(out.join("report.html"), html(study)).map_err(|e| e.to_string())
}
