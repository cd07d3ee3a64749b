//! The paper's observations, each answered by a sentence computed from the measurements
//! (never hand-written numbers), for the report and study.json.

use super::{Lighting, SceneStudy};

fn ratio(s: &SceneStudy, bsdf: &str, l: Lighting) -> Option<(f64, f64)> {
    s.results.iter().find(|r| r.model.bsdf == bsdf && r.lighting == l).map(|r| r.ratio)
}

fn pct(r: f64) -> f64 {
    (r - 1.0) * 100.0
}

/// One sentence per observation that the scenes at hand can answer.
pub fn answers(studies: &[SceneStudy]) -> Vec<String> {
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
        if let (Some(g), Some(d)) = (ratio(s, "wolff", Lighting::Global), ratio(s, "wolff", Lighting::Direct)) {
            out.push(format!(
                "{}: Wolff (IOR 1.4) changes the image-mean luminance by {:+.1} % ± {:.1} % under global illumination and {:+.1} % ± {:.1} % under direct lighting.",
                s.name,
                pct(g.0),
                g.1 * 100.0,
                pct(d.0),
                d.1 * 100.0
            ));
        }
        let darkest = s
            .results
            .iter()
            .filter(|r| r.lighting == Lighting::Global)
            .min_by(|a, b| a.ratio.0.total_cmp(&b.ratio.0))
            .map(|r| (r.model.label, r.ratio.0));
        if let Some((label, r)) = darkest {
            out.push(format!("{}: the darkest model under global illumination is {label} ({:+.1} % against Lambert).", s.name, pct(r)));
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
                out.push(format!("{}, region \"{name}\": Oren–Nayar is {verdict}: ratio {m:.3} ± {hw:.3} (99 %).", s.name));
            }
        }
    }
    out
}
