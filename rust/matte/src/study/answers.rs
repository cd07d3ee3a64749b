//! The paper's observations, each answered by a sentence computed from the measurements
//! (never hand-written numbers), for the report, study.json and the terminal; each section
//! ([`super::section::Section::answers`]) gives the sentences of its part.

use super::configuration::{Configuration, VARIANTS, main_run};
use super::convergence::Series;
use super::main_run::SceneStudy;
use super::options::Lighting;
use super::perceptual::{Agreement, Answer, PerceptualStudy, Visibility};
use super::ratio::{Ratio, Relation, Verdict};
use super::truth::TruthStudy;
use super::variants::VariantStudy;

fn ratio(s: &SceneStudy, model: Configuration, l: Lighting) -> Option<Ratio> {
    s.result(model, l).map(|r| r.ratio)
}

/// Decimals that show a half-width `hw` with one significant digit, at least `min`, at most
/// `min + 3`.
fn decimals(hw: f64, min: usize) -> usize {
    if !(hw > 0.0) || !hw.is_finite() {
        return min;
    }
    ((-hw.log10().floor()) as i64).clamp(min as i64, min as i64 + 3) as usize
}

/// `ratio ± half-width`, with the decimals its half-width needs.
pub(crate) fn ci(r: Ratio) -> String {
    let d = decimals(r.half_width, 3);
    format!("{:.*} ± {:.*}", d, r.value, d, r.half_width)
}

/// A difference (or a ratio's change against 1) in percent: `+x % ± y %`.
fn pct_ci(r: Ratio) -> String {
    let d = decimals(r.half_width * 100.0, 1);
    format!("{:+.*} % ± {:.*} %", d, r.value * 100.0, d, r.half_width * 100.0)
}

/// [`pct_ci`] for other modules (the report's tables).
pub(crate) fn pct(r: Ratio) -> String {
    pct_ci(r)
}

/// A FLIP value with its interval, with the decimals its half-width needs.
pub(crate) fn flip_ci(r: Ratio) -> String {
    let d = decimals(r.half_width, 3);
    format!("{:.*} ± {:.*}", d, r.value, d, r.half_width)
}

/// A ratio's change against Lambert's 1.
fn change(r: Ratio) -> Ratio {
    r.minus(Ratio::exact(1.0))
}

/// Whether the reference of a perceptual answer is Lambert (else the model's surface).
fn against_lambert(a: &Answer) -> bool {
    a.reference == Configuration::Lambert
}

/// The perceptual question over every scene lit globally: how many differences are more or
/// less visible under global illumination, against Lambert and against the surfaces.
pub fn perceptual_summary(studies: &[PerceptualStudy]) -> Vec<String> {
    let mut out = Vec::new();
    for (lambert, what) in
        [(true, "a model's difference to Lambert"), (false, "a rough model's difference from its own surface")]
    {
        let all: Vec<&Answer> = studies
            .iter()
            .flat_map(|p| &p.answers)
            .filter(|a| against_lambert(a) == lambert && !(lambert && a.model.is_truth()))
            .filter(|a| a.visibility != Visibility::DirectOnly)
            .collect();
        if all.is_empty() {
            continue;
        }
        let count = |v: Visibility| all.iter().filter(|a| a.visibility == v).count();
        let agree = all.iter().filter(|a| a.agreement == Agreement::Agree).count();
        let disagree = all.iter().filter(|a| a.agreement == Agreement::Disagree).count();
        out.push(format!(
            "Perceptual question (HDR-FLIP: is {what} more or less visible under global illumination?): more visible in {} of {} scene×model cases, less visible in {}, undecided in {}, within the noise floor in {} (99 % jackknife interval of ΔFLIP; scenes lit directly only left out). The energy answer (Δ) agrees in {agree} and points the other way in {disagree}.",
            count(Visibility::MoreVisible),
            all.len(),
            count(Visibility::LessVisible),
            count(Visibility::Undecided),
            count(Visibility::WithinNoise),
        ));
    }
    out
}

/// Per scene, one sentence per reference kind: each model's mean FLIP in both lightings and
/// the verdict, with the noise floors.
pub fn perceptual_scene_answers(p: &PerceptualStudy) -> Vec<String> {
    let mut out = Vec::new();
    let floor = |l: Lighting| p.floor(l).map(|f| flip_ci(f.mean.value)).unwrap_or_default();
    for lambert in [true, false] {
        let parts: Vec<String> = p
            .answers
            .iter()
            .filter(|a| against_lambert(a) == lambert)
            .filter_map(|a| {
                let g = p.comparison(a.model, a.reference, Lighting::Global)?;
                let d = p.comparison(a.model, a.reference, Lighting::Direct)?;
                let against = if lambert { String::new() } else { format!(" / {}", a.reference.label()) };
                Some(if p.direct_only {
                    format!("{}{against} {}", a.model.label(), flip_ci(g.flip.mean.value))
                } else {
                    format!(
                        "{}{against} {} global, {} direct: {}",
                        a.model.label(),
                        flip_ci(g.flip.mean.value),
                        flip_ci(d.flip.mean.value),
                        a.visibility.name()
                    )
                })
            })
            .collect();
        if parts.is_empty() {
            continue;
        }
        let what = if lambert { "against Lambert" } else { "against its own surface" };
        out.push(if p.direct_only {
            format!(
                "{}: mean HDR-FLIP {what} (the scene is lit directly only; noise floor {}): {}.",
                p.scene_name,
                floor(Lighting::Global),
                parts.join("; ")
            )
        } else {
            format!(
                "{}: mean HDR-FLIP {what} (noise floor {} global, {} direct): {}.",
                p.scene_name,
                floor(Lighting::Global),
                floor(Lighting::Direct),
                parts.join("; ")
            )
        });
    }
    out
}

/// The closing note: where the perceptual and the energy answers differ.
pub fn perceptual_closing(studies: &[PerceptualStudy]) -> Option<String> {
    let decided: Vec<(&PerceptualStudy, &Answer)> = studies
        .iter()
        .flat_map(|p| p.answers.iter().map(move |a| (p, a)))
        .filter(|(_, a)| a.visibility != Visibility::DirectOnly && !(against_lambert(a) && a.model.is_truth()))
        .collect();
    if decided.is_empty() {
        return None;
    }
    let describe = |(p, a): &(&PerceptualStudy, &Answer)| {
        let against = if against_lambert(a) { "Lambert".to_string() } else { a.reference.label().to_string() };
        format!(
            "{} {} vs {against} (energy {}, Δ = {}; perceptual {}, ΔFLIP = {})",
            p.scene_name,
            a.model.label(),
            a.energy_verdict.name(),
            pct_ci(a.energy),
            a.visibility.name(),
            flip_ci(a.delta)
        )
    };
    let list = |g: Agreement| -> Vec<String> { decided.iter().filter(|x| x.1.agreement == g).map(describe).collect() };
    let (opposite, energy_only, perceptual_only) =
        (list(Agreement::Disagree), list(Agreement::EnergyOnly), list(Agreement::PerceptualOnly));
    if opposite.is_empty() && energy_only.is_empty() && perceptual_only.is_empty() {
        return Some(format!(
            "Perceptual against energy: the two answers agree in every one of the {} scene×model cases.",
            decided.len()
        ));
    }
    let mut parts = Vec::new();
    if !opposite.is_empty() {
        parts.push(format!("they point opposite ways in {}: {}", opposite.len(), opposite.join("; ")));
    }
    if !energy_only.is_empty() {
        parts.push(format!(
            "the energy answer is decided but the perceptual one is not in {}: {}",
            energy_only.len(),
            energy_only.join("; ")
        ));
    }
    if !perceptual_only.is_empty() {
        parts.push(format!(
            "the perceptual answer is decided but the energy one is not in {}: {}",
            perceptual_only.len(),
            perceptual_only.join("; ")
        ));
    }
    Some(format!(
        "Where the perceptual and the energy answers differ (of {} scene×model cases): {}.",
        decided.len(),
        parts.join(". And ")
    ))
}

/// The paper's question over every scene, then per scene: Wolff's change, van Ginneken's
/// rank, the darkest model and Oren–Nayar in the named regions.
pub fn scene_answers(studies: &[SceneStudy]) -> Vec<String> {
    let mut out = Vec::new();
    // The paper's question: does the difference to Lambert grow under global illumination?
    let (mut grow, mut total) = (0, 0);
    for s in studies {
        for m in &main_run()[1..] {
            if let (Some(g), Some(d)) = (ratio(s, *m, Lighting::Global), ratio(s, *m, Lighting::Direct))
                && (g.value - d.value).abs() > 1e-9
            {
                total += 1;
                grow += ((g.value - 1.0).abs() > (d.value - 1.0).abs()) as usize;
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
        let wolff = Configuration::WolffPhysical;
        let direct_only = match (ratio(s, wolff, Lighting::Global), ratio(s, wolff, Lighting::Direct)) {
            (Some(g), Some(d)) => (g.value - d.value).abs() <= 1e-9,
            _ => false,
        };
        if let (Some(g), Some(d)) = (ratio(s, wolff, Lighting::Global), ratio(s, wolff, Lighting::Direct)) {
            out.push(if direct_only {
                format!("{}: Wolff (IOR 1.4) changes the image-mean luminance by {} (the scene is lit directly only).", s.name, pct_ci(change(d)))
            } else {
                format!(
                    "{}: Wolff (IOR 1.4) changes the image-mean luminance by {} under global illumination and {} under direct lighting.",
                    s.name,
                    pct_ci(change(g)),
                    pct_ci(change(d))
                )
            });
        }
        // The paper's "Ginneken darkest": van Ginneken's rank among the models (1 = darkest).
        let mut global: Vec<_> =
            s.results.iter().filter(|r| r.lighting == Lighting::Global && !r.model.is_truth()).collect();
        global.sort_by(|a, b| a.ratio.value.total_cmp(&b.ratio.value));
        if let (Some(rank), Some(on)) = (
            global.iter().position(|r| r.model == Configuration::Ginneken),
            ratio(s, Configuration::OrenNayarQualitative, Lighting::Global),
        ) {
            let vg = global[rank].ratio;
            let versus = vg.relation_to(on).brightness();
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
            .filter(|r| r.lighting == Lighting::Global && !r.model.is_truth())
            .min_by(|a, b| a.ratio.value.total_cmp(&b.ratio.value))
            .map(|r| (r.model.label(), r.ratio));
        if let Some((label, r)) = darkest {
            let setting = if direct_only { "" } else { " under global illumination" };
            out.push(format!(
                "{}: the darkest model{setting} is {label} ({} against Lambert).",
                s.name,
                pct_ci(change(r))
            ));
        }
        if let Some(r) = s.result(Configuration::OrenNayarQualitative, Lighting::Global) {
            for region in &r.regions {
                let verdict = match region.ratio.relation_to_one() {
                    Relation::Above => "brighter than Lambert (a glow)",
                    Relation::Below => "darker than Lambert (no glow)",
                    Relation::Indistinguishable => "not distinguishable from Lambert",
                };
                out.push(format!(
                    "{}, region \"{}\": Oren–Nayar is {verdict}: ratio {} (99 %).",
                    s.name,
                    region.name,
                    ci(region.ratio)
                ));
            }
        }
    }
    out
}

/// The paper's question against the true surfaces, over every scene lit globally.
pub fn truth_summary(truths: &[TruthStudy]) -> Option<String> {
    let verdicts: Vec<Verdict> = truths
        .iter()
        .flat_map(|t| t.models().into_iter().filter_map(|m| t.growth(m).map(|g| g.1)))
        .filter(|v| *v != Verdict::DirectOnly)
        .collect();
    if verdicts.is_empty() {
        return None;
    }
    let count = |v: Verdict| verdicts.iter().filter(|x| **x == v).count();
    Some(format!(
        "Question against the true surfaces (does a rough model's difference from the surface it describes grow under global illumination?): it grows in {} of {} scene×model cases, shrinks in {} and is undecided in {} (99 % interval of Δ; scenes lit directly only left out).",
        count(Verdict::Grows),
        verdicts.len(),
        count(Verdict::Shrinks),
        count(Verdict::Undecided)
    ))
}

/// The paper's question against the true surfaces: per model, its ratio to its own surface
/// and whether the difference grows under global illumination; per lighting, the closest model.
pub fn truth_answers(t: &TruthStudy) -> Vec<String> {
    let mut out = Vec::new();
    for m in t.models() {
        let (Some(g), Some(d), Some((delta, verdict))) =
            (t.comparison(m, Lighting::Global), t.comparison(m, Lighting::Direct), t.growth(m))
        else {
            continue;
        };
        let surface = g.truth.label();
        out.push(match verdict {
            Verdict::DirectOnly => format!(
                "{}: {} / its surface, {surface}, = {} (the scene is lit directly only).",
                t.scene_name,
                m.label(),
                ci(g.ratio)
            ),
            Verdict::Undecided => format!(
                "{}: {} / its surface, {surface}, = {} under global illumination and {} under direct lighting; whether the difference grows under global illumination is undecided (Δ = {}, the interval contains 0).",
                t.scene_name,
                m.label(),
                ci(g.ratio),
                ci(d.ratio),
                pct_ci(delta)
            ),
            v => format!(
                "{}: {} / its surface, {surface}, = {} under global illumination and {} under direct lighting; the difference from the surface {} under global illumination (Δ = {}).",
                t.scene_name,
                m.label(),
                ci(g.ratio),
                ci(d.ratio),
                v.name(),
                pct_ci(delta)
            ),
        });
    }
    out.extend(closest_answers(t));
    out
}

/// Per lighting: the model closest to its own surface, and by how much.
pub fn closest_answers(t: &TruthStudy) -> Vec<String> {
    let mut out = Vec::new();
    let lightings: &[Lighting] =
        if t.direct_only { &[Lighting::Direct] } else { &[Lighting::Global, Lighting::Direct] };
    for &l in lightings {
        let ranking = t.ranking(l);
        let Some(best) = ranking.first() else { continue };
        let setting = if t.direct_only { String::new() } else { format!(", {} lighting", l.name()) };
        let next = match ranking.get(1) {
            Some(n) => format!(
                "; the next, {}, is {} off its surface, {:.1} percentage points further",
                n.model.label(),
                pct_ci(change(n.ratio)),
                100.0 * ((n.ratio.value - 1.0).abs() - (best.ratio.value - 1.0).abs())
            ),
            None => String::new(),
        };
        out.push(format!(
            "{}{setting}: the model closest to its own surface is {}, {} off {}{next}.",
            t.scene_name,
            best.model.label(),
            pct_ci(change(best.ratio)),
            best.truth.label()
        ));
    }
    out
}

/// Wolff's normalisation and the Oren–Nayar model: how the ratio to Lambert changes.
pub fn variant_answers(v: &VariantStudy) -> Vec<String> {
    let mut out = Vec::new();
    let get = |c: Configuration, l: Lighting| v.result(c, l).map(|r| r.ratio);
    let wolff: Vec<Configuration> = VARIANTS.iter().copied().filter(|x| x.bsdf() == "wolff").collect();
    let spread = |l: Lighting| -> Option<Ratio> {
        let rs: Vec<Ratio> = wolff.iter().filter_map(|x| get(*x, l)).collect();
        let hi = rs.iter().copied().max_by(|a, b| a.value.total_cmp(&b.value))?;
        let lo = rs.iter().copied().min_by(|a, b| a.value.total_cmp(&b.value))?;
        Some(hi.minus(lo))
    };
    let parts: Vec<String> = wolff
        .iter()
        .filter_map(|x| {
            let g = get(*x, Lighting::Global)?;
            let (_, value) = x.property()?;
            Some(format!("{value} {} ({} Lambert)", ci(g), g.relation_to_one().brightness()))
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
        let verdict = match g.relation_to(d) {
            Relation::Above => "global illumination amplifies the normalisation's effect",
            Relation::Below => "global illumination reduces the normalisation's effect",
            Relation::Indistinguishable => "global and direct lighting are not distinguishable here",
        };
        out.push(format!(
            "{}: the Wolff normalisations span {} of Lambert's image mean under global illumination and {} under direct lighting, so {verdict}.",
            v.scene_name,
            pct_ci(g).trim_start_matches('+'),
            pct_ci(d).trim_start_matches('+')
        ));
    }
    for l in [Lighting::Global, Lighting::Direct] {
        if let (Some(q), Some(f)) = (get(Configuration::OrenNayarQualitative, l), get(Configuration::OrenNayarFull, l))
        {
            let d = f.minus(q);
            let verdict = d.relation_to(Ratio::exact(0.0)).brightness();
            out.push(format!(
                "{}, {} lighting: the full Oren–Nayar model is {verdict} the qualitative one. Its ratio to Lambert is {} against {} (difference {}).",
                v.scene_name,
                l.name(),
                ci(f),
                ci(q),
                pct_ci(d)
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
    for model in [Configuration::OrenNayarQualitative, Configuration::OrenNayarFull] {
        let label = model.label();
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
        let relations: Vec<Relation> =
            s.renderers.iter().filter_map(|r| s.best(model, r).map(|p| p.ratio.relation_to_one())).collect();
        let same_side = relations.windows(2).all(|w| w[0] == w[1]);
        let brightness = match (same_side, relations.first()) {
            (true, Some(Relation::Below)) => "darker than Lambert there, so there is no glow",
            (true, Some(Relation::Above)) => "brighter than Lambert there: a glow",
            (true, Some(Relation::Indistinguishable)) => "not distinguishable from Lambert there",
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
        .and_then(|v| v.result(Configuration::OrenNayarFull, Lighting::Global))
        .and_then(|r| r.regions.iter().find(|x| x.name == s.region))
    {
        out.push(format!(
            "{}, region \"{}\", variant run at the study's full budget: Oren–Nayar full / Lambert = {} ({} Lambert).",
            s.scene_name,
            s.region,
            ci(r.ratio),
            r.ratio.relation_to_one().brightness()
        ));
    }
    out
}
