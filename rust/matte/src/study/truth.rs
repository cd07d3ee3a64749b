//! The paper's question restated against the true surfaces (docs/study.md, true surfaces):
//! each rough model against the simulated microsurface it describes
//! ([`Configuration::true_surface`], tables from `docs/microgeometry.md`), per scene and
//! lighting. The surfaces are rendered in the main run ([`super::main_run`]) with the
//! models' seeds, so the ratio model / surface is paired per pass like every ratio to
//! Lambert; Oren–Nayar full comes from the variants where they ran, else it is rendered here.
//!
//! Per model: the ratio with its 99 % interval under global and direct lighting, and
//! Δ = |r_global − 1| − |r_direct − 1| ([`metrics::growth`]): does the model's error against
//! its surface grow or shrink under global illumination? Per scene and lighting: the model
//! closest to its own surface. Per lighting: the heatmap strip (model − surface) / surface.

use super::configuration::{Configuration, WITH_TRUTH};
use super::main_run::{SceneStudy, derived_scene};
use super::options::{Lighting, StudyOptions, image_defines, load_regions};
use super::ratio::{Ratio, Verdict};
use super::render::{keep_passes, render_side};
use super::variants::VariantStudy;
use super::{metrics, strip};
use glam::DVec3;
use matte_render::film::Image;
use matte_render::image_io;
use std::path::PathBuf;

/// One model against its true surface in one lighting.
pub struct Comparison {
    pub model: Configuration,
    pub truth: Configuration,
    pub lighting: Lighting,
    /// Image-mean luminance ratio model / surface (paired passes) with its 99 % interval.
    pub ratio: Ratio,
    /// The per-pass ratios, in seed order.
    pub pass_ratios: Vec<f64>,
}

/// One scene's models against their true surfaces.
pub struct TruthStudy {
    pub scene_name: String,
    pub comparisons: Vec<Comparison>,
    /// Heatmap strip (model − surface) / surface per lighting, relative to the output
    /// folder, with its colour-scale half-range.
    pub strips: Vec<(Lighting, PathBuf, f32)>,
    /// The scene's own max_depth is 2: global and direct are the same image.
    pub direct_only: bool,
    /// Oren–Nayar full's derived scene, when it was rendered here (relative to the output folder).
    pub scene_file: Option<PathBuf>,
}

impl TruthStudy {
    /// `model` against its surface in `lighting`.
    pub fn comparison(&self, model: Configuration, lighting: Lighting) -> Option<&Comparison> {
        self.comparisons.iter().find(|c| c.model == model && c.lighting == lighting)
    }

    /// The models compared, in [`WITH_TRUTH`]'s order.
    pub fn models(&self) -> Vec<Configuration> {
        WITH_TRUTH.into_iter().filter(|m| self.comparisons.iter().any(|c| c.model == *m)).collect()
    }

    /// Δ = |r_global − 1| − |r_direct − 1| with its interval, and the verdict on it.
    pub fn growth(&self, model: Configuration) -> Option<(Ratio, Verdict)> {
        let g = self.comparison(model, Lighting::Global)?;
        let d = self.comparison(model, Lighting::Direct)?;
        let delta = metrics::growth(&g.pass_ratios, &d.pass_ratios);
        Some((delta, Verdict::of(delta, self.direct_only)))
    }

    /// The models in `lighting` from the closest to its own surface (smallest |ratio − 1|).
    pub fn ranking(&self, lighting: Lighting) -> Vec<&Comparison> {
        let mut v: Vec<&Comparison> = self.comparisons.iter().filter(|c| c.lighting == lighting).collect();
        v.sort_by(|a, b| (a.ratio.value - 1.0).abs().total_cmp(&(b.ratio.value - 1.0).abs()));
        v
    }
}

/// Passes [`run`] renders for a scene (Oren–Nayar full when the variants do not).
pub fn pass_count(opts: &StudyOptions, scene_name: &str) -> u64 {
    if opts.variants_for(scene_name) { 0 } else { 2 * opts.passes as u64 }
}

/// Compares every model of [`WITH_TRUTH`] with its true surface in both lightings, and writes
/// the heatmap strips. `None` when the main run has no true surfaces (see its notes).
pub fn run(
    study: &SceneStudy,
    variants: Option<&VariantStudy>,
    opts: &StudyOptions,
    progress: &dyn Fn(&str, u32),
) -> Result<Option<TruthStudy>, String> {
    if !WITH_TRUTH.iter().filter_map(|m| m.true_surface()).all(|t| study.result(t, Lighting::Global).is_some()) {
        return Ok(None);
    }
    let rel_dir = PathBuf::from(&study.name).join("truth");
    let regions = load_regions(&study.scene)?;
    let full = Configuration::OrenNayarFull;
    let mut scene_file = None;
    let mut comparisons = Vec::new();
    let mut strips = Vec::new();
    for lighting in [Lighting::Global, Lighting::Direct] {
        let mut tiles = Vec::new();
        let mut rels = Vec::new();
        for model in WITH_TRUTH {
            let (pass_means, mean): (Vec<DVec3>, Image) = if let Some(r) = study.result(model, lighting) {
                (r.pass_means.clone(), r.mean.clone())
            } else if let Some(r) = variants.and_then(|v| v.result(model, lighting)) {
                (r.pass_means.clone(), r.mean.clone())
            } else if model == full {
                let file = match &scene_file {
                    Some(f) => f,
                    None => scene_file.insert(derived_scene(&study.scene, full, opts, &rel_dir)?),
                };
                let what = format!("{} {} {}", study.name, lighting.name(), full.label());
                let defines = image_defines(opts, full.bsdf(), lighting);
                let side = render_side(
                    &opts.out.join(file),
                    opts,
                    defines,
                    &regions,
                    &opts.out.join(&rel_dir).join("work"),
                    &|k| progress(&what, k),
                )?;
                keep_passes(opts, &study.name, lighting, full.key(), &side)?;
                let mean = side.moments.mean_image();
                image_io::write_exr(
                    &opts.out.join(&rel_dir).join(format!("{}_{}.exr", lighting.name(), full.key())),
                    &mean,
                )?;
                (side.moments.pass_means, mean)
            } else {
                return Err(format!("no {} image to compare with its surface", model.label()));
            };
            let truth = model.true_surface().expect("WITH_TRUTH has surfaces");
            let t = study.result(truth, lighting).ok_or_else(|| format!("no {} image", truth.label()))?;
            let pass_ratios = metrics::pass_ratios(&pass_means, &t.pass_means);
            comparisons.push(Comparison {
                model,
                truth,
                lighting,
                ratio: metrics::mean_ci99(&pass_ratios),
                pass_ratios,
            });
            let rel = metrics::relative_difference(&mean, &t.mean, 1e-4);
            tiles.push((model.tile(), mean.width, mean.height));
            rels.push(rel);
        }
        let range = metrics::heatmap_range(&rels);
        let diff_tiles: Vec<strip::StripTile> = tiles
            .iter()
            .zip(&rels)
            .map(|((label, w, h), rel)| strip::StripTile::from_difference(label, *w, *h, rel, range))
            .collect();
        let path = rel_dir.join(format!("difference_{}.png", lighting.name()));
        strip::write_strip(&opts.out.join(&path), &diff_tiles)?;
        strips.push((lighting, path, range));
    }
    // A scene whose own max_depth is 2 renders the same image in both settings.
    let direct_only = WITH_TRUTH.iter().all(|m| {
        let pair = |l| comparisons.iter().find(|c: &&Comparison| c.model == *m && c.lighting == l);
        match (pair(Lighting::Global), pair(Lighting::Direct)) {
            (Some(g), Some(d)) => g.pass_ratios.iter().zip(&d.pass_ratios).all(|(a, b)| (a - b).abs() <= 1e-9),
            _ => false,
        }
    });
    Ok(Some(TruthStudy { scene_name: study.name.clone(), comparisons, strips, direct_only, scene_file }))
}
