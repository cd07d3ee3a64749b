//! The report's sections for the model variants ([`super::variants`]) and the convergence
//! series ([`super::convergence`]): study.json fragments, HTML tables, strips and a small
//! SVG plot of the region ratio against spp with its 99 % intervals.

use super::convergence::{self, Series};
use super::variants::{VARIANTS, VariantStudy};
use super::{Lighting, answers};
use serde_json::json;
use std::fmt::Write as _;

pub(super) fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

pub fn variants_json(v: &VariantStudy) -> serde_json::Value {
    let rows: Vec<_> = VARIANTS
        .iter()
        .filter_map(|x| {
            let g = v.result(x.key, Lighting::Global)?;
            let d = v.result(x.key, Lighting::Direct)?;
            Some(json!({
                "key": x.key, "bsdf": x.bsdf, "label": x.label, "property": { x.property.0: x.property.1 },
                "main_run": x.main, "meaning": x.meaning,
                "scene_file": g.scene_file,
                "ratio_global": g.ratio.0, "ratio_global_ci99": g.ratio.1,
                "ratio_direct": d.ratio.0, "ratio_direct_ci99": d.ratio.1,
                "seconds_global": g.seconds, "seconds_direct": d.seconds,
                "exr_global": g.exr, "exr_direct": d.exr,
                "regions": super::report::regions_json(&g.regions, &d.regions),
            }))
        })
        .collect();
    json!({
        "scene": v.scene_name,
        "strips": v.strips.iter().map(|(l, a, b, range)| json!({"lighting": l.name(), "strip": a, "difference": b, "difference_range": range})).collect::<Vec<_>>(),
        "variants": rows,
        "answers": answers::variant_answers(v),
    })
}

pub fn variants_html(v: &VariantStudy) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        r#"<div class="scene"><h2>{}: model variants</h2><p>Wolff's constant K and the Oren–Nayar model, each set as a property in a derived copy of the scene
(<code>{}/variants/*.xml</code>). The defaults are the main run's images. The other variants use the main run's seeds and budget, so their ratio to Lambert is paired with the same Lambert passes.
n = 1.4, F = Fresnel reflectance, F<sub>dr</sub> = its cosine-weighted hemispherical average (docs/models.md: Wolff normalisations, Oren-Nayar qualitative and full).</p><ul>"#,
        esc(&v.scene_name),
        esc(&v.scene_name)
    );
    for x in VARIANTS {
        let _ = write!(
            h,
            "<li><b>{}</b> (<code>{}={}</code>): {}</li>",
            esc(x.label),
            x.property.0,
            x.property.1,
            esc(x.meaning)
        );
    }
    h.push_str("</ul>");
    for (l, strip, diff, range) in &v.strips {
        h.push_str(&super::report::strips_html(*l, strip, diff, *range, "variant"));
    }
    h.push_str("<table><tr><th>variant</th><th>ratio, global</th><th>ratio, direct</th><th>Δ</th><th>source</th></tr>");
    for x in VARIANTS {
        let (Some(g), Some(d)) = (v.result(x.key, Lighting::Global), v.result(x.key, Lighting::Direct)) else {
            continue;
        };
        let _ = write!(
            h,
            "<tr><td>{}</td><td>{:.4} ± {:.4}</td><td>{:.4} ± {:.4}</td><td>{:+.4}</td>",
            esc(x.label),
            g.ratio.0,
            g.ratio.1,
            d.ratio.0,
            d.ratio.1,
            (g.ratio.0 - 1.0).abs() - (d.ratio.0 - 1.0).abs()
        );
        match &g.scene_file {
            Some(f) => {
                let _ = write!(h, r#"<td class="l"><a href="{}">derived scene</a></td></tr>"#, f.display());
            }
            None => h.push_str(r#"<td class="l">main run</td></tr>"#),
        }
    }
    h.push_str("</table>");
    let names: Vec<String> =
        v.results.first().map(|r| r.regions.iter().map(|x| x.0.clone()).collect()).unwrap_or_default();
    for (i, name) in names.iter().enumerate() {
        let _ = write!(
            h,
            "<h4>Region: {}</h4><table><tr><th>variant</th><th>ratio, global</th><th>ratio, direct</th></tr>",
            esc(name)
        );
        for x in VARIANTS {
            let (Some(g), Some(d)) = (v.result(x.key, Lighting::Global), v.result(x.key, Lighting::Direct)) else {
                continue;
            };
            let (Some(gr), Some(dr)) = (g.regions.get(i), d.regions.get(i)) else { continue };
            let _ = write!(
                h,
                "<tr><td>{}</td><td>{:.4} ± {:.4}</td><td>{:.4} ± {:.4}</td></tr>",
                esc(x.label),
                gr.1,
                gr.2,
                dr.1,
                dr.2
            );
        }
        h.push_str("</table>");
    }
    h.push_str("</div>");
    h
}

pub fn convergence_json(s: &Series) -> serde_json::Value {
    let models: Vec<&str> = convergence::SERIES_MODELS[1..].iter().map(|m| m.key).collect();
    json!({
        "scene": s.scene_name, "region": s.region, "lighting": "global",
        "film": s.film, "crop": s.crop, "passes": s.passes, "spp_levels": s.levels, "renderers": s.renderers,
        "notes": s.notes,
        "points": s.points.iter().map(|p| json!({
            "spp": p.spp, "renderer": p.renderer, "model": p.model, "ratio": p.ratio.0, "ratio_ci99": p.ratio.1, "seconds": p.seconds,
        })).collect::<Vec<_>>(),
        "stable_levels": models.iter().map(|m| json!({
            "model": m,
            "per_renderer": s.renderers.iter().map(|r| { let (k, n) = s.stable(m, r); json!({"renderer": r, "overlapping_highest": k, "levels": n}) }).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "renderer_agreement": models.iter().map(|m| { let (k, n) = s.agreement(m); json!({"model": m, "overlapping": k, "levels": n}) }).collect::<Vec<_>>(),
        "answers": answers::convergence_answers(s, None),
    })
}

const COLOURS: [&str; 2] = ["#1f77b4", "#d95f02"];

/// Region ratio against spp (log axis), one series per renderer with 99 % error bars, and
/// Lambert's level (1) dashed when it is within the data's range (else an arrow says where).
fn plot(s: &Series, model: &str, title: &str) -> String {
    let (w, h, left, right, top, bottom) = (470.0, 250.0, 58.0, 12.0, 40.0, 36.0);
    let pts: Vec<&convergence::Point> = s.points.iter().filter(|p| p.model == model).collect();
    if pts.is_empty() || s.levels.is_empty() {
        return String::new();
    }
    let mut lo = pts.iter().map(|p| p.ratio.0 - p.ratio.1).fold(f64::INFINITY, f64::min);
    let mut hi = pts.iter().map(|p| p.ratio.0 + p.ratio.1).fold(f64::NEG_INFINITY, f64::max);
    let pad = ((hi - lo) * 0.15).max(0.002);
    lo -= pad;
    hi += pad;
    let n = s.levels.len();
    let x_of = |i: usize, r: usize| left + (w - left - right) * (i as f64 + 0.5) / n as f64 + (r as f64 - 0.5) * 10.0;
    let y_of = |v: f64| top + (h - top - bottom) * (hi - v) / (hi - lo);
    let mut g = String::new();
    let _ = write!(
        g,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" style="font:12px system-ui,sans-serif;margin:4px 12px 4px 0">"#
    );
    let _ = write!(g, r#"<text x="{left}" y="16" font-weight="bold">{}</text>"#, esc(title));
    let _ = write!(
        g,
        r##"<rect x="{left}" y="{top}" width="{}" height="{}" fill="none" stroke="#999"/>"##,
        w - left - right,
        h - top - bottom
    );
    for k in 0..=4 {
        let v = lo + (hi - lo) * k as f64 / 4.0;
        let y = y_of(v);
        let _ = write!(
            g,
            r##"<line x1="{}" x2="{left}" y1="{y:.1}" y2="{y:.1}" stroke="#999"/><text x="{}" y="{:.1}" text-anchor="end">{v:.3}</text>"##,
            left - 4.0,
            left - 6.0,
            y + 4.0
        );
    }
    if (lo..=hi).contains(&1.0) {
        let y1 = y_of(1.0);
        let _ = write!(
            g,
            r##"<line x1="{left}" x2="{}" y1="{y1:.1}" y2="{y1:.1}" stroke="#444" stroke-dasharray="4 3"/><text x="{}" y="{:.1}" text-anchor="end" fill="#444">Lambert</text>"##,
            w - right,
            w - right - 4.0,
            y1 - 4.0
        );
    } else {
        let (y, arrow) = if hi < 1.0 { (top + 14.0, "↑ above") } else { (h - bottom - 6.0, "↓ below") };
        let _ = write!(
            g,
            r##"<text x="{}" y="{y:.1}" text-anchor="end" fill="#444">Lambert (1) {arrow} the plot</text>"##,
            w - right - 6.0
        );
    }
    for (i, spp) in s.levels.iter().enumerate() {
        let _ = write!(
            g,
            r#"<text x="{:.1}" y="{}" text-anchor="middle">{spp}</text>"#,
            x_of(i, 0) + 5.0,
            h - bottom + 16.0
        );
    }
    let _ = write!(
        g,
        r#"<text x="{:.1}" y="{}" text-anchor="middle">total spp</text>"#,
        left + (w - left - right) / 2.0,
        h - 4.0
    );
    for (r, name) in s.renderers.iter().enumerate() {
        let c = COLOURS[r % 2];
        let mut line = Vec::new();
        for (i, spp) in s.levels.iter().enumerate() {
            let Some(p) = s.point(model, name, *spp) else { continue };
            let x = x_of(i, r);
            let (ya, yb, ym) = (y_of(p.ratio.0 - p.ratio.1), y_of(p.ratio.0 + p.ratio.1), y_of(p.ratio.0));
            let _ = write!(
                g,
                r#"<line x1="{x:.1}" x2="{x:.1}" y1="{ya:.1}" y2="{yb:.1}" stroke="{c}"/><line x1="{:.1}" x2="{:.1}" y1="{ya:.1}" y2="{ya:.1}" stroke="{c}"/><line x1="{:.1}" x2="{:.1}" y1="{yb:.1}" y2="{yb:.1}" stroke="{c}"/><circle cx="{x:.1}" cy="{ym:.1}" r="3" fill="{c}"/>"#,
                x - 3.0,
                x + 3.0,
                x - 3.0,
                x + 3.0
            );
            line.push(format!("{x:.1},{ym:.1}"));
        }
        let _ = write!(g, r#"<polyline points="{}" fill="none" stroke="{c}" stroke-opacity="0.5"/>"#, line.join(" "));
        let _ = write!(g, r#"<text x="{}" y="32" fill="{c}">● {}</text>"#, left + 150.0 * r as f64, esc(name));
    }
    g.push_str("</svg>");
    g
}

pub fn convergence_html(s: &Series, variants: Option<&VariantStudy>) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        r#"<div class="scene"><h2>{}: convergence in the region "{}" (global illumination)</h2>
<p>Is the paper's Oren–Nayar "glow" real or a bias? The region ratio to Lambert is rendered at increasing total spp by matte and by Mitsuba. {} paired passes per level, and each level has its own seeds.
Only the region's pixels are rendered: the film is cropped to x {}…{}, y {}…{} of {}×{} (derived scenes in <code>{}/convergence/</code>). A real effect stays within its 99 % intervals as spp grows, and the two renderers' intervals overlap.
A bias or noise artefact drifts with spp or differs between the renderers.</p>"#,
        esc(&s.scene_name),
        esc(&s.region),
        s.passes,
        s.crop[0],
        s.crop[0] + s.crop[2] - 1,
        s.crop[1],
        s.crop[1] + s.crop[3] - 1,
        s.film[0],
        s.film[1],
        esc(&s.scene_name)
    );
    for n in &s.notes {
        let _ = write!(h, r#"<p class="note">{}</p>"#, esc(n));
    }
    for m in &convergence::SERIES_MODELS[1..] {
        h.push_str(&plot(s, m.key, &format!("{} / Lambert", m.label)));
    }
    h.push_str("<table><tr><th>total spp</th>");
    for m in &convergence::SERIES_MODELS[1..] {
        for r in &s.renderers {
            let _ = write!(h, "<th>{}, {}</th>", esc(m.label), esc(r));
        }
        if s.renderers.len() == 2 {
            h.push_str("<th>overlap</th>");
        }
    }
    h.push_str("</tr>");
    for spp in &s.levels {
        let _ = write!(h, "<tr><td>{spp}</td>");
        for m in &convergence::SERIES_MODELS[1..] {
            let pts: Vec<Option<&convergence::Point>> = s.renderers.iter().map(|r| s.point(m.key, r, *spp)).collect();
            for p in &pts {
                match p {
                    Some(p) => {
                        let _ = write!(h, "<td>{:.4} ± {:.4}</td>", p.ratio.0, p.ratio.1);
                    }
                    None => h.push_str("<td>–</td>"),
                }
            }
            if let [Some(a), Some(b)] = pts.as_slice() {
                h.push_str(if convergence::overlap(a.ratio, b.ratio) { "<td>yes</td>" } else { "<td><b>no</b></td>" });
            } else if s.renderers.len() == 2 {
                h.push_str("<td>–</td>");
            }
        }
        h.push_str("</tr>");
    }
    h.push_str("</table>");
    if let Some(r) = variants
        .and_then(|v| v.result("oren_nayar_full", Lighting::Global))
        .and_then(|r| r.regions.iter().find(|x| x.0 == s.region))
    {
        let _ = write!(
            h,
            r#"<p class="small">The model-variant run at the study's full budget (whole image) gives Oren–Nayar full / Lambert = {:.4} ± {:.4} in this region.</p>"#,
            r.1, r.2
        );
    }
    h.push_str("<ul>");
    for a in answers::convergence_answers(s, variants) {
        let _ = write!(h, "<li>{}</li>", esc(&a));
    }
    h.push_str("</ul></div>");
    h
}
