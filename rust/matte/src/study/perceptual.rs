//! Is a difference visible, and is it more or less visible under global illumination? The
//! perceptual side of the study (docs/study.md, "Perceptual difference"): HDR-FLIP (Andersson
//! et al. 2020, 2021), computed by NVIDIA's reference implementation (the `flip-evaluator`
//! package, through `python -m matte_mitsuba.perceptual` in the Python side), per scene, model
//! and lighting:
//! - each model and true surface against Lambert, and each rough model against its own surface;
//! - the **noise floor**: Lambert against Lambert rendered with other seeds at the same budget;
//! - per value, the mean and the 95th percentile of the per-pixel FLIP map of the two mean
//!   images, each with a 99 % jackknife interval over the passes (pass k left out of both
//!   images of a pair, which share its seed).
//!
//! Every comparison of a scene and lighting uses one exposure range: the one HDR-FLIP derives
//! from that lighting's Lambert image. The verdict per model: ΔFLIP = FLIP_global −
//! FLIP_direct with its paired jackknife interval (pass k left out in both lightings). The
//! difference is *more visible* under global illumination when the interval lies above 0,
//! *less visible* below 0 and *undecided* when it contains 0. It is *within the noise* when
//! either lighting's FLIP interval does not lie entirely above its noise floor's. Beside it
//! is the energy verdict on Δ ([`super::metrics::growth`]) and whether the two agree.

use super::configuration::{Configuration, TRUTHS, WITH_TRUTH, main_run};
use super::main_run::SceneStudy;
use super::options::{Lighting, Region, StudyOptions, image_defines};
use super::ratio::{Ratio, Verdict};
use super::render::{keep_passes, kept_pass_file, kept_passes_dir, render_side};
use super::truth::TruthStudy;
use super::{font, strip};
use statrs::distribution::{ContinuousCDF, StudentsT};
use std::path::{Path, PathBuf};

/// Seed offset of the noise floor's second Lambert render (its pass k uses seed + this + k):
/// far from the study's own seeds and the convergence series'.
pub const FLOOR_SEED_OFFSET: u64 = 1 << 32;

/// The key of the noise floor's second Lambert render.
pub const FLOOR_KEY: &str = "lambert_other_seeds";

/// Renders the noise floor's second Lambert (other seeds, same budget) and keeps its passes.
pub fn render_floor(
    scene: &Path,
    scene_name: &str,
    lighting: Lighting,
    regions: &[Region],
    opts: &StudyOptions,
    progress: &dyn Fn(u32),
) -> Result<(), String> {
    if !opts.perceptual {
        return Ok(());
    }
    let other = StudyOptions { seed: opts.seed.wrapping_add(FLOOR_SEED_OFFSET), ..opts.clone() };
    let defines = image_defines(opts, Configuration::Lambert.bsdf(), lighting);
    let work = opts.out.join(scene_name).join("work");
    let side = render_side(scene, &other, defines, regions, &work, progress)?;
    keep_passes(opts, scene_name, lighting, FLOOR_KEY, &side)
}

/// Passes the perceptual step renders per scene (the noise floor's Lambert in both lightings).
pub fn pass_count(opts: &StudyOptions) -> u64 {
    if opts.perceptual { 2 * opts.passes as u64 } else { 0 }
}

/// A FLIP statistic of one pair: the value of the full-budget images with its 99 % jackknife
/// interval, and the leave-one-out values it came from.
#[derive(Clone, Debug)]
pub struct Flip {
    pub value: Ratio,
    pub replicates: Vec<f64>,
}

impl Flip {
    fn new(value: f64, replicates: Vec<f64>) -> Flip {
        Flip { value: jackknife_ci99(value, &replicates), replicates }
    }

    /// `self − other` paired per left-out pass: value and jackknife interval.
    pub fn minus(&self, other: &Flip) -> Ratio {
        let reps: Vec<f64> = self.replicates.iter().zip(&other.replicates).map(|(a, b)| a - b).collect();
        jackknife_ci99(self.value.value - other.value.value, &reps)
    }
}

/// `value` with the 99 % Student-t interval of the jackknife standard error of its K
/// leave-one-out `replicates` (K − 1 degrees of freedom): se² = (K − 1)/K Σ (θᵢ − θ̄)².
pub fn jackknife_ci99(value: f64, replicates: &[f64]) -> Ratio {
    let k = replicates.len();
    if k < 2 {
        return Ratio::new(value, f64::INFINITY);
    }
    let kf = k as f64;
    let m = replicates.iter().sum::<f64>() / kf;
    let se = ((kf - 1.0) / kf * replicates.iter().map(|x| (x - m).powi(2)).sum::<f64>()).sqrt();
    let q = StudentsT::new(0.0, 1.0, kf - 1.0).map(|t| t.inverse_cdf(0.995)).unwrap_or(f64::INFINITY);
    Ratio::new(value, q * se)
}

/// Mean and 95th percentile of a FLIP map.
#[derive(Clone, Debug)]
pub struct FlipPair {
    pub mean: Flip,
    pub p95: Flip,
}

/// One pair: `model` against `reference` (Lambert, its surface, or Lambert itself for the
/// noise floor) in one lighting.
#[derive(Clone, Debug)]
pub struct Comparison {
    pub model: Configuration,
    pub reference: Configuration,
    pub lighting: Lighting,
    pub flip: FlipPair,
}

/// HDR-FLIP's exposure range of one lighting (from its Lambert image).
#[derive(Clone, Debug, serde::Deserialize, serde::Serialize)]
pub struct Exposure {
    pub start: f64,
    pub stop: f64,
    pub count: u32,
    pub tonemapper: String,
    pub pixels_per_degree: f64,
}

/// Whether a difference is more or less visible under global illumination.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Visibility {
    /// ΔFLIP's interval lies above 0.
    MoreVisible,
    /// ΔFLIP's interval lies below 0.
    LessVisible,
    /// ΔFLIP's interval contains 0.
    Undecided,
    /// In one lighting at least, the FLIP interval does not lie above the noise floor's.
    WithinNoise,
    /// The scene is lit directly only.
    DirectOnly,
}

impl Visibility {
    /// The verdict as the report and study.json write it.
    pub fn name(self) -> &'static str {
        match self {
            Visibility::MoreVisible => "more visible",
            Visibility::LessVisible => "less visible",
            Visibility::Undecided => "undecided",
            Visibility::WithinNoise => "within the noise",
            Visibility::DirectOnly => "direct only",
        }
    }
}

/// How the perceptual verdict relates to the energy verdict (Δ of the luminance ratios).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Agreement {
    /// Both decided, the same direction (grows & more visible, shrinks & less visible).
    Agree,
    /// Both decided, opposite directions.
    Disagree,
    /// The energy answer is decided, the perceptual one is not (undecided or within the noise).
    EnergyOnly,
    /// The perceptual answer is decided, the energy one is not.
    PerceptualOnly,
    /// Neither is decided, or the scene is lit directly only.
    Neither,
}

impl Agreement {
    /// How the energy verdict and the perceptual one relate.
    pub fn of(energy: Verdict, perceptual: Visibility) -> Agreement {
        let e = match energy {
            Verdict::Grows => Some(true),
            Verdict::Shrinks => Some(false),
            _ => None,
        };
        let p = match perceptual {
            Visibility::MoreVisible => Some(true),
            Visibility::LessVisible => Some(false),
            _ => None,
        };
        match (e, p) {
            (Some(a), Some(b)) if a == b => Agreement::Agree,
            (Some(_), Some(_)) => Agreement::Disagree,
            (Some(_), None) => Agreement::EnergyOnly,
            (None, Some(_)) => Agreement::PerceptualOnly,
            (None, None) => Agreement::Neither,
        }
    }

    /// The relation as the report and study.json write it.
    pub fn name(self) -> &'static str {
        match self {
            Agreement::Agree => "agree",
            Agreement::Disagree => "disagree",
            Agreement::EnergyOnly => "energy only",
            Agreement::PerceptualOnly => "perceptual only",
            Agreement::Neither => "neither decided",
        }
    }
}

/// The answer for one model against one reference: ΔFLIP and both verdicts.
#[derive(Clone, Debug)]
pub struct Answer {
    pub model: Configuration,
    pub reference: Configuration,
    /// FLIP_global − FLIP_direct of the map means, paired jackknife interval.
    pub delta: Ratio,
    pub visibility: Visibility,
    /// Δ = |r_global − 1| − |r_direct − 1| of the luminance ratios, and its verdict.
    pub energy: Ratio,
    pub energy_verdict: Verdict,
    pub agreement: Agreement,
}

/// One scene's perceptual differences.
pub struct PerceptualStudy {
    pub scene_name: String,
    /// "flip-evaluator <version>".
    pub implementation: String,
    /// Wall time of the HDR-FLIP evaluations (both lightings side by side).
    pub seconds: f64,
    pub exposures: Vec<(Lighting, Exposure)>,
    /// Per lighting: Lambert against Lambert with other seeds.
    pub floors: Vec<(Lighting, FlipPair)>,
    pub comparisons: Vec<Comparison>,
    /// Per lighting: the FLIP strip against Lambert (noise floor first) and against the
    /// surfaces (relative to the output folder; the second may be missing).
    pub strips: Vec<(Lighting, PathBuf, Option<PathBuf>)>,
    pub direct_only: bool,
    pub answers: Vec<Answer>,
}

impl PerceptualStudy {
    /// The noise floor of `lighting`.
    pub fn floor(&self, lighting: Lighting) -> Option<&FlipPair> {
        self.floors.iter().find(|(l, _)| *l == lighting).map(|(_, f)| f)
    }

    /// `model` against `reference` in lighting `l`.
    pub fn comparison(&self, model: Configuration, reference: Configuration, l: Lighting) -> Option<&Comparison> {
        self.comparisons.iter().find(|c| c.model == model && c.reference == reference && c.lighting == l)
    }

    /// HDR-FLIP's exposure range of lighting `l`.
    pub fn exposure(&self, l: Lighting) -> Option<&Exposure> {
        self.exposures.iter().find(|(x, _)| *x == l).map(|(_, e)| e)
    }

    /// Whether the comparison's mean FLIP lies above its lighting's noise floor (intervals
    /// disjoint).
    pub fn above_floor(&self, c: &Comparison) -> bool {
        self.floor(c.lighting).is_some_and(|f| c.flip.mean.value.low() > f.mean.value.high())
    }
}

/// What `python -m matte_mitsuba.perceptual` writes.
#[derive(serde::Deserialize)]
struct ResultFile {
    implementation: String,
    groups: Vec<GroupResult>,
}

#[derive(serde::Deserialize)]
struct GroupResult {
    name: String,
    exposure: Exposure,
    comparisons: Vec<PairResult>,
}

#[derive(serde::Deserialize)]
struct PairResult {
    name: String,
    width: u32,
    height: u32,
    mean: f64,
    p95: f64,
    jackknife_mean: Vec<f64>,
    jackknife_p95: Vec<f64>,
}

/// One pair to evaluate: (model, reference, lighting).
type Pair = (Configuration, Configuration, Lighting);

fn pair_name((m, r, _): Pair) -> String {
    format!("{}/{}", m.key(), r.key())
}

/// The noise floor is written as Lambert against Lambert.
fn is_floor((m, r, _): Pair) -> bool {
    m == Configuration::Lambert && r == Configuration::Lambert
}

/// HDR-FLIP of every pair of the scene, the noise floors, strips and verdicts. `Err` is a
/// note for the report (the Python side or flip-evaluator missing, a failed evaluation): the
/// rest of the study stands without it.
pub fn run(study: &SceneStudy, truths: Option<&TruthStudy>, opts: &StudyOptions) -> Result<PerceptualStudy, String> {
    let dir = kept_passes_dir(opts, &study.name);
    let result = evaluate(study, truths, opts, &dir);
    let _ = std::fs::remove_dir_all(&dir);
    result
}

fn evaluate(
    study: &SceneStudy,
    truths: Option<&TruthStudy>,
    opts: &StudyOptions,
    dir: &Path,
) -> Result<PerceptualStudy, String> {
    let started = std::time::Instant::now();
    let k = opts.passes as usize;
    let files = |l: Lighting, key: &str| -> Option<Vec<PathBuf>> {
        let v: Vec<PathBuf> = (0..k).map(|i| kept_pass_file(dir, l, key, i)).collect();
        v.iter().all(|p| p.is_file()).then_some(v)
    };
    // A scene whose own max_depth is 2 renders the same image in both settings: one group.
    let direct_only = study.direct_only();
    let lightings: &[Lighting] = if direct_only { &[Lighting::Global] } else { &[Lighting::Global, Lighting::Direct] };
    let lambert = Configuration::Lambert;
    let mut pairs_by_group: Vec<(Lighting, Vec<Pair>)> = Vec::new();
    let mut groups = Vec::new();
    let maps = dir.join("maps");
    std::fs::create_dir_all(&maps).map_err(|e| format!("{}: {e}", maps.display()))?;
    for &l in lightings {
        let lambert_files = files(l, lambert.key()).ok_or("the Lambert passes were not kept")?;
        let mut pairs: Vec<(Pair, Vec<PathBuf>, Vec<PathBuf>)> = Vec::new();
        let floor = files(l, FLOOR_KEY).ok_or("the noise floor's Lambert passes were not kept")?;
        pairs.push(((lambert, lambert, l), lambert_files.clone(), floor));
        for m in main_run().into_iter().skip(1).chain(TRUTHS) {
            if let Some(f) = files(l, m.key()) {
                pairs.push(((m, lambert, l), lambert_files.clone(), f));
            }
        }
        if truths.is_some() {
            for m in WITH_TRUTH {
                let t = m.true_surface().expect("WITH_TRUTH has surfaces");
                if let (Some(fm), Some(ft)) = (files(l, m.key()), files(l, t.key())) {
                    pairs.push(((m, t, l), ft, fm));
                }
            }
        }
        let comparisons: Vec<serde_json::Value> = pairs
            .iter()
            .map(|(p, r, t)| {
                serde_json::json!({
                    "name": pair_name(*p),
                    "reference": r,
                    "test": t,
                    "map": maps.join(format!("{}_{}_{}.f32", l.name(), p.0.key(), p.1.key())),
                })
            })
            .collect();
        groups.push(serde_json::json!({"name": l.name(), "exposure": lambert_files, "comparisons": comparisons}));
        pairs_by_group.push((l, pairs.into_iter().map(|(p, _, _)| p).collect()));
    }
    // One process per lighting, run side by side.
    let python = crate::installation::python_side()?;
    let mut children = Vec::new();
    for (group, (l, _)) in groups.iter().zip(&pairs_by_group) {
        let job = dir.join(format!("job_{}.json", l.name()));
        let out = dir.join(format!("result_{}.json", l.name()));
        std::fs::write(&job, serde_json::json!({ "groups": [group] }).to_string())
            .map_err(|e| format!("{}: {e}", job.display()))?;
        let child = python
            .module("perceptual")
            .arg(&job)
            .arg("--out")
            .arg(&out)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .map_err(|e| format!("cannot start {}: {e}", python.python.display()))?;
        children.push((child, out));
    }
    let mut implementation = String::new();
    let mut result_groups = Vec::new();
    let mut failure = None;
    for (child, out) in children {
        let output = child.wait_with_output().map_err(|e| e.to_string())?;
        if !output.status.success() {
            // flip-evaluator reports some errors on stdout.
            let text =
                format!("{}\n{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
            let line = text.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("failed without a message");
            failure.get_or_insert(format!("python -m matte_mitsuba.perceptual ({}): {line}", python.python.display()));
            continue;
        }
        let text = std::fs::read_to_string(&out).map_err(|e| format!("{}: {e}", out.display()))?;
        let result: ResultFile = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", out.display()))?;
        implementation = result.implementation;
        result_groups.extend(result.groups);
    }
    if let Some(f) = failure {
        return Err(f);
    }
    let out = dir.join("result_*.json");
    if result_groups.len() != pairs_by_group.len() {
        return Err(format!("{}: {} groups, expected {}", out.display(), result_groups.len(), pairs_by_group.len()));
    }
    let mut exposures = Vec::new();
    let mut floors = Vec::new();
    let mut comparisons = Vec::new();
    let mut strips = Vec::new();
    for ((l, pairs), g) in pairs_by_group.iter().zip(result_groups) {
        if g.name != l.name() || g.comparisons.len() != pairs.len() {
            return Err(format!("{}: group {} does not match the job", out.display(), g.name));
        }
        let mut lambert_tiles = Vec::new();
        let mut surface_tiles = Vec::new();
        for (p, c) in pairs.iter().zip(&g.comparisons) {
            if c.name != pair_name(*p) {
                return Err(format!("{}: {} where the job has {}", out.display(), c.name, pair_name(*p)));
            }
            let finite = |xs: &[f64]| xs.iter().all(|x| x.is_finite());
            if !(c.mean.is_finite() && c.p95.is_finite() && finite(&c.jackknife_mean) && finite(&c.jackknife_p95))
                || c.jackknife_mean.len() != k
                || c.jackknife_p95.len() != k
            {
                return Err(format!("{}: {}: not K = {k} finite jackknife values", out.display(), c.name));
            }
            let flip = FlipPair {
                mean: Flip::new(c.mean, c.jackknife_mean.clone()),
                p95: Flip::new(c.p95, c.jackknife_p95.clone()),
            };
            let map = read_map(&maps.join(format!("{}_{}_{}.f32", l.name(), p.0.key(), p.1.key())), c.width, c.height)?;
            let label = if is_floor(*p) { "noise floor" } else { p.0.tile() };
            let tile = map_tile(label, c.width, c.height, &map);
            if p.1 == lambert {
                lambert_tiles.push(tile)
            } else {
                surface_tiles.push(tile)
            }
            if is_floor(*p) {
                floors.push((*l, flip));
            } else {
                comparisons.push(Comparison { model: p.0, reference: p.1, lighting: *l, flip });
            }
        }
        let write = |tiles: &mut Vec<strip::StripTile>, what: &str| -> Result<Option<PathBuf>, String> {
            if tiles.is_empty() {
                return Ok(None);
            }
            let h = tiles[0].height;
            tiles.push(colour_bar(h));
            let path = PathBuf::from(&study.name).join(format!("flip_{what}_{}.png", l.name()));
            std::fs::create_dir_all(opts.out.join(&study.name)).map_err(|e| e.to_string())?;
            strip::write_strip(&opts.out.join(&path), tiles)?;
            Ok(Some(path))
        };
        let against_lambert = write(&mut lambert_tiles, "lambert")?.ok_or("no FLIP map against Lambert")?;
        let against_surface = write(&mut surface_tiles, "surface")?;
        strips.push((*l, against_lambert, against_surface));
        exposures.push((*l, g.exposure));
    }
    if direct_only {
        // The direct setting is the same image: the same values.
        let copy: Vec<Comparison> =
            comparisons.iter().map(|c| Comparison { lighting: Lighting::Direct, ..c.clone() }).collect();
        comparisons.extend(copy);
        if let Some((_, f)) = floors.first().cloned() {
            floors.push((Lighting::Direct, f));
        }
        if let Some((_, e)) = exposures.first().cloned() {
            exposures.push((Lighting::Direct, e));
        }
    }
    let mut p = PerceptualStudy {
        scene_name: study.name.clone(),
        implementation,
        seconds: started.elapsed().as_secs_f64(),
        exposures,
        floors,
        comparisons,
        strips,
        direct_only,
        answers: Vec::new(),
    };
    p.answers = answers(&p, study, truths);
    Ok(p)
}

/// ΔFLIP and the energy Δ with their verdicts, for every model with both lightings.
fn answers(p: &PerceptualStudy, study: &SceneStudy, truths: Option<&TruthStudy>) -> Vec<Answer> {
    let mut out = Vec::new();
    for c in p.comparisons.iter().filter(|c| c.lighting == Lighting::Global) {
        let Some(d) = p.comparison(c.model, c.reference, Lighting::Direct) else { continue };
        let delta = c.flip.mean.minus(&d.flip.mean);
        let visibility = if p.direct_only {
            Visibility::DirectOnly
        } else if !(p.above_floor(c) && p.above_floor(d)) {
            Visibility::WithinNoise
        } else if delta.low() > 0.0 {
            Visibility::MoreVisible
        } else if delta.high() < 0.0 {
            Visibility::LessVisible
        } else {
            Visibility::Undecided
        };
        let energy = if c.reference == Configuration::Lambert {
            study.growth(c.model)
        } else {
            truths.and_then(|t| t.growth(c.model)).map(|(delta, _)| delta)
        };
        let Some(energy) = energy else { continue };
        let energy_verdict = Verdict::of(energy, p.direct_only);
        out.push(Answer {
            model: c.model,
            reference: c.reference,
            delta,
            visibility,
            energy,
            energy_verdict,
            agreement: Agreement::of(energy_verdict, visibility),
        });
    }
    out
}

fn read_map(path: &Path, width: u32, height: u32) -> Result<Vec<f32>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if bytes.len() != (width * height * 4) as usize {
        return Err(format!("{}: {} bytes, expected {width}×{height} float32", path.display(), bytes.len()));
    }
    Ok(bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect())
}

/// A FLIP map in FLIP's own colour map (magma over [0, 1]).
pub fn map_tile(label: &str, width: u32, height: u32, map: &[f32]) -> strip::StripTile {
    let rgb = map.iter().flat_map(|&v| colorous::MAGMA.eval_continuous(v.clamp(0.0, 1.0) as f64).as_array()).collect();
    strip::StripTile { label: label.to_string(), width, height, rgb }
}

/// The colour bar of the FLIP strips: magma from 0 (bottom) to 1 (top), its ticks labelled.
pub fn colour_bar(height: u32) -> strip::StripTile {
    const BAR: u32 = 14;
    const TICK_PX: f32 = 12.0;
    let ink = image::Rgb([20, 20, 20]);
    let width = (BAR as f32 + 4.0 + font::width("0.5", TICK_PX)).max(font::width("FLIP", strip::LABEL_PX) + 2.0).ceil();
    let (ascent, descent) = font::extent(TICK_PX);
    let text_h = ascent - descent;
    let (width, h) = (width as u32, height.max((2.0 * text_h).ceil() as u32));
    let mut img = image::RgbImage::from_fn(width, h, |x, y| {
        let v = 1.0 - y as f64 / (h - 1) as f64;
        image::Rgb(if x < BAR { colorous::MAGMA.eval_continuous(v).as_array() } else { [255, 255, 255] })
    });
    let x = BAR as f32 + 4.0;
    font::draw(&mut img, x, 0.0, "1", TICK_PX, ink);
    if h as f32 >= 3.0 * text_h {
        font::draw(&mut img, x, ((h as f32 - text_h) / 2.0).round(), "0.5", TICK_PX, ink);
    }
    font::draw(&mut img, x, h as f32 - text_h, "0", TICK_PX, ink);
    strip::StripTile { label: "FLIP".into(), width, height: h, rgb: img.into_raw() }
}
