//! The paper's observations, each answered by a sentence computed from the measurements
//! (never hand-written numbers), for the report and study.json.

use super::convergence::Series;
use super::variants::VariantStudy;
use super::{Lighting, SceneStudy, Study};

fn ratio(s: &SceneStudy, bsdf: &str, l: Lighting) -> Option<(f64, f64)> {
    s.results.iter().find(|r| r.model.bsdf == bsdf && r.lighting == l).map(|r| r.ratio)
}

/// Decimals that show a half-width `hw` with one significant digit, at least `min`, at most
/// `min + 3`.
fn decimals(hw: f64, min: usize) -> usize {
    if !(hw > 0.0) || !hw.is_finite() {
        return min;
    }
    ((-hw.log10().floor()) as i64).clamp(min as i64, min as i64 + 3) as usize
}

/// `ratio ± half-width`.
fn ci(r: (f64, f64)) -> String {
    let d = decimals(r.1, 3);
    format!("{:.*} ± {:.*}", d, r.0, d, r.1)
}

/// A ratio's change against 1 (or a difference) in percent: `+x % ± y %`.
fn pct_ci(delta: f64, hw: f64) -> String {
    let d = decimals(hw * 100.0, 1);
    format!("{:+.*} % ± {:.*} %", d, delta * 100.0, d, hw * 100.0)
}

/// Relation of a ratio to Lambert (1), decided by its 99 % interval.
fn relation(r: (f64, f64)) -> &'static str {
    if r.0 - r.1 > 1.0 {
        "brighter than"
    } else if r.0 + r.1 < 1.0 {
        "darker than"
    } else {
        "not distinguishable from"
    }
}

/// One sentence per observation that the measurements at hand can answer.
pub fn answers(study: &Study) -> Vec<String> {
    let mut out = scene_answers(&study.scenes);
    for v in &study.variants {
        out.extend(variant_answers(v));
    }
    for s in &study.convergence {
        out.extend(convergence_answers(s, study.variants.iter().find(|v| v.scene_name == s.scene_name)));
    }
    out
}

fn scene_answers(studies: &[SceneStudy]) -> Vec<String> {
    let mut out = Vec::new();
    // The paper's question: does the difference to Lambert grow under global illumination?
    let (mut grow, mut total) = (0, 0);
    for s in studies {
        for m in &super::MODELS[1..] {
            if let (Some(g), Some(d)) = (ratio(s, m.bsdf, Lighting::Global), ratio(s, m.bsdf, Lighting::Direct))
                && (g.0 - d.0).abs() > 1e-9
            {
                total += 1;
                grow += ((g.0 - 1.0).abs() > (d.0 - 1.0).abs()) as usize;
            }
        }
    }
    if total > 0 {
        out.push(format!(
            "Question (does the difference to Lambert grow under global illumination?): it grows in {grow} of {total} scene×model cases whose global and direct images differ (|ratio − 1| larger with global illumination)."
        ));
    }
    for s in studies {
        // A scene whose own max_depth is 2 (the bunny, as the paper's figure 1) renders the same
        // image in both settings (up to the order in which tiles reach the film).
        let direct_only = match (ratio(s, "wolff", Lighting::Global), ratio(s, "wolff", Lighting::Direct)) {
            (Some(g), Some(d)) => (g.0 - d.0).abs() <= 1e-9,
            _ => false,
        };
        if let (Some(g), Some(d)) = (ratio(s, "wolff", Lighting::Global), ratio(s, "wolff", Lighting::Direct)) {
            out.push(if direct_only {
                format!("{}: Wolff (IOR 1.4) changes the image-mean luminance by {} (the scene is lit directly only).", s.name, pct_ci(d.0 - 1.0, d.1))
            } else {
                format!(
                    "{}: Wolff (IOR 1.4) changes the image-mean luminance by {} under global illumination and {} under direct lighting.",
                    s.name,
                    pct_ci(g.0 - 1.0, g.1),
                    pct_ci(d.0 - 1.0, d.1)
                )
            });
        }
        // The paper's "Ginneken darkest": van Ginneken's rank among the models (1 = darkest).
        let mut global: Vec<_> = s.results.iter().filter(|r| r.lighting == Lighting::Global).collect();
        global.sort_by(|a, b| a.ratio.0.total_cmp(&b.ratio.0));
        if let (Some(rank), Some(on)) =
            (global.iter().position(|r| r.model.bsdf == "ginneken"), ratio(s, "oren_nayar", Lighting::Global))
        {
            let vg = global[rank].ratio;
            let versus = if vg.0 + vg.1 < on.0 - on.1 {
                "darker than"
            } else if vg.0 - vg.1 > on.0 + on.1 {
                "brighter than"
            } else {
                "not distinguishable from"
            };
            out.push(format!(
                "{}: van Ginneken ranks {} of {} from the darkest ({} against Lambert) and is {versus} Oren–Nayar ({}).",
                s.name,
                rank + 1,
                global.len(),
                ci(vg),
                ci(on)
            ));
        }
        let darkest = s
            .results
            .iter()
            .filter(|r| r.lighting == Lighting::Global)
            .min_by(|a, b| a.ratio.0.total_cmp(&b.ratio.0))
            .map(|r| (r.model.label, r.ratio));
        if let Some((label, r)) = darkest {
            let setting = if direct_only { "" } else { " under global illumination" };
            out.push(format!(
                "{}: the darkest model{setting} is {label} ({} against Lambert).",
                s.name,
                pct_ci(r.0 - 1.0, r.1)
            ));
        }
        for r in s.results.iter().filter(|r| r.model.bsdf == "oren_nayar" && r.lighting == Lighting::Global) {
            for (name, m, hw) in &r.regions {
                let verdict = if m - hw > 1.0 {
                    "brighter than Lambert (a glow)"
                } else if m + hw < 1.0 {
                    "darker than Lambert (no glow)"
                } else {
                    "not distinguishable from Lambert"
                };
                out.push(format!(
                    "{}, region \"{name}\": Oren–Nayar is {verdict}: ratio {} (99 %).",
                    s.name,
                    ci((*m, *hw))
                ));
            }
        }
    }
    out
}

/// Wolff's normalisation and the Oren–Nayar model: how the ratio to Lambert changes.
pub fn variant_answers(v: &VariantStudy) -> Vec<String> {
    let mut out = Vec::new();
    let get = |key: &str, l: Lighting| v.result(key, l).map(|r| r.ratio);
    let wolff: Vec<_> = super::variants::VARIANTS.iter().filter(|x| x.bsdf == "wolff").collect();
    let spread = |l: Lighting| -> Option<(f64, f64)> {
        let rs: Vec<(f64, f64)> = wolff.iter().filter_map(|x| get(x.key, l)).collect();
        let hi = rs.iter().copied().max_by(|a, b| a.0.total_cmp(&b.0))?;
        let lo = rs.iter().copied().min_by(|a, b| a.0.total_cmp(&b.0))?;
        Some((hi.0 - lo.0, (hi.1 * hi.1 + lo.1 * lo.1).sqrt()))
    };
    let parts: Vec<String> = wolff
        .iter()
        .filter_map(|x| {
            let g = get(x.key, Lighting::Global)?;
            Some(format!("{} {} ({} Lambert)", x.property.1, ci(g), relation(g)))
        })
        .collect();
    if !parts.is_empty() {
        out.push(format!(
            "{}: the paper's \"Wolff darker\" depends on the normalisation. The image-mean ratio to Lambert under global illumination is {}.",
            v.scene_name,
            parts.join("; ")
        ));
    }
    if let (Some(g), Some(d)) = (spread(Lighting::Global), spread(Lighting::Direct)) {
        let verdict = if g.0 - g.1 > d.0 + d.1 {
            "global illumination amplifies the normalisation's effect"
        } else if g.0 + g.1 < d.0 - d.1 {
            "global illumination reduces the normalisation's effect"
        } else {
            "global and direct lighting are not distinguishable here"
        };
        out.push(format!(
            "{}: the Wolff normalisations span {} of Lambert's image mean under global illumination and {} under direct lighting, so {verdict}.",
            v.scene_name,
            pct_ci(g.0, g.1).trim_start_matches('+'),
            pct_ci(d.0, d.1).trim_start_matches('+')
        ));
    }
    for l in [Lighting::Global, Lighting::Direct] {
        if let (Some(q), Some(f)) = (get("oren_nayar_qualitative", l), get("oren_nayar_full", l)) {
            let d = (f.0 - q.0, (f.1 * f.1 + q.1 * q.1).sqrt());
            let verdict = if d.0 - d.1 > 0.0 {
                "brighter than"
            } else if d.0 + d.1 < 0.0 {
                "darker than"
            } else {
                "not distinguishable from"
            };
            out.push(format!(
                "{}, {} lighting: the full Oren–Nayar model is {verdict} the qualitative one. Its ratio to Lambert is {} against {} (difference {}).",
                v.scene_name,
                l.name(),
                ci(f),
                ci(q),
                pct_ci(d.0, d.1)
            ));
        }
    }
    out
}

/// The "glow" question: stable over spp, the same in both renderers?
pub fn convergence_answers(s: &Series, variants: Option<&VariantStudy>) -> Vec<String> {
    let mut out = Vec::new();
    let (lo, hi) = match (s.levels.first(), s.levels.last()) {
        (Some(a), Some(b)) => (*a, *b),
        _ => return out,
    };
    for (model, label) in [("oren_nayar", "Oren–Nayar"), ("oren_nayar_full", "Oren–Nayar full")] {
        let per_renderer: Vec<String> = s
            .renderers
            .iter()
            .filter_map(|r| {
                let first = s.point(model, r, lo)?;
                let best = s.best(model, r)?;
                let (k, n) = s.stable(model, r);
                Some(format!(
                    "{r}: {} at {} spp, {} at {} spp; {k} of {n} levels overlap the {}-spp interval",
                    ci(first.ratio),
                    first.spp,
                    ci(best.ratio),
                    best.spp,
                    best.spp
                ))
            })
            .collect();
        if per_renderer.is_empty() {
            continue;
        }
        let stable = s.renderers.iter().all(|r| {
            let (k, n) = s.stable(model, r);
            n > 0 && k == n
        });
        let (ak, an) = s.agreement(model);
        let best: Vec<(f64, f64)> = s.renderers.iter().filter_map(|r| s.best(model, r).map(|p| p.ratio)).collect();
        let rel: Vec<&str> = best.iter().map(|r| relation(*r)).collect();
        let same_side = rel.windows(2).all(|w| w[0] == w[1]);
        let brightness = match (same_side, rel.first()) {
            (true, Some(&"darker than")) => "darker than Lambert there, so there is no glow",
            (true, Some(&"brighter than")) => "brighter than Lambert there: a glow",
            (true, Some(_)) => "not distinguishable from Lambert there",
            _ => "on different sides of Lambert in the two renderers",
        };
        let verdict = if s.renderers.len() < 2 {
            format!(
                "Stable over spp: {}. Only one renderer ran, so agreement is untested. The model is {brightness}.",
                if stable { "yes" } else { "no (it drifts)" }
            )
        } else if stable && ak == an && an > 0 {
            format!(
                "The ratio is stable over spp, and the renderers agree at {ak} of {an} levels. It is a converged property of the model, not a bias or noise artefact. The model is {brightness}."
            )
        } else if !stable {
            format!(
                "The ratio drifts with spp (renderers agree at {ak} of {an} levels), so noise or a bias affects it at low spp. At the highest level the model is {brightness}."
            )
        } else {
            format!(
                "The ratio is stable over spp, but the renderers agree at only {ak} of {an} levels, which means a renderer bias. The model is {brightness}."
            )
        };
        out.push(format!(
            "{}, region \"{}\", {label} / Lambert under global illumination, {lo}–{hi} spp, 99 % intervals. {}. {verdict}",
            s.scene_name,
            s.region,
            per_renderer.join("; ")
        ));
    }
    if let Some(r) = variants
        .and_then(|v| v.result("oren_nayar_full", Lighting::Global))
        .and_then(|r| r.regions.iter().find(|x| x.0 == s.region))
    {
        out.push(format!(
            "{}, region \"{}\", variant run at the study's full budget: Oren–Nayar full / Lambert = {} ({} Lambert).",
            s.scene_name,
            s.region,
            ci((r.1, r.2)),
            relation((r.1, r.2))
        ));
    }
    out
}
