//! Model variants (docs/study.md, model variants): how the results change with Wolff's normalisation
//! and with the Oren–Nayar model. Each variant is one property in the `$bsdf` element, set
//! through a derived scene ([`super::variant_scene`]) that both renderers load like any
//! scene. The variants that are the plugins' defaults are the main run itself; the others
//! are rendered with the main run's seeds and budget, so their ratio to Lambert is paired
//! with the Lambert passes already rendered.
//!
//! What the variants mean: `docs/models.md#oren-nayar-qualitative`, `#oren-nayar-full` and
//! `#wolff-normalisations` (Wolff's constant K), with matte's choices.

use super::configuration::{Configuration, VARIANTS};
use super::main_run::{SceneStudy, derived_scene, region_ratios};
use super::options::{Lighting, StudyOptions, image_defines, load_regions};
use super::ratio::{Ratio, RegionRatio};
use super::render::{keep_passes, render_side};
use super::{metrics, strip};
use glam::DVec3;
use matte_render::film::Image;
use matte_render::image_io;
use std::path::PathBuf;

/// One variant in one lighting setting.
pub struct VariantResult {
    pub variant: Configuration,
    pub lighting: Lighting,
    /// Image-mean luminance ratio to Lambert (paired passes) with its 99 % interval.
    pub ratio: Ratio,
    /// Per named region: ratio to Lambert.
    pub regions: Vec<RegionRatio>,
    /// Per-pass image means, in seed order.
    pub pass_means: Vec<DVec3>,
    /// Mean image.
    pub mean: Image,
    /// Render time; `None` for the main run's images.
    pub seconds: Option<f64>,
    /// Mean image (EXR), relative to the output folder.
    pub exr: PathBuf,
    /// The derived scene, relative to the output folder (`None` for the main run's).
    pub scene_file: Option<PathBuf>,
}

/// One scene's model variants.
pub struct VariantStudy {
    pub scene_name: String,
    pub results: Vec<VariantResult>,
    /// Image strip and heatmap strip per lighting, relative to the output folder.
    pub strips: Vec<(Lighting, PathBuf, PathBuf, f32)>,
}

impl VariantStudy {
    /// `variant` in `lighting`, if it was rendered.
    pub fn result(&self, variant: Configuration, lighting: Lighting) -> Option<&VariantResult> {
        self.results.iter().find(|r| r.variant == variant && r.lighting == lighting)
    }
}

/// Passes the variants of one scene render (for the progress bar).
pub fn pass_count(passes: u32) -> u64 {
    (VARIANTS.iter().filter(|v| !v.is_main_run()).count() * 2) as u64 * passes as u64
}

/// Renders the non-default variants of `study`'s scene in both lightings, paired with its
/// Lambert passes, and writes the derived scenes, EXRs and strips.
pub fn run(study: &SceneStudy, opts: &StudyOptions, progress: &dyn Fn(&str, u32)) -> Result<VariantStudy, String> {
    let rel_dir = PathBuf::from(&study.name).join("variants");
    let dir = opts.out.join(&rel_dir);
    let regions = load_regions(&study.scene)?;
    let mut results = Vec::new();
    let mut strips = Vec::new();
    for lighting in [Lighting::Global, Lighting::Direct] {
        let lambert = study.lambert(lighting).ok_or("the main run has no Lambert passes")?;
        let lambert_img = lambert.moments.mean_image();
        let mut images: Vec<(&str, Image)> = vec![("Lambert", lambert_img.clone())];
        for v in VARIANTS {
            let (ratio, regs, seconds, exr, scene_file, mean, pass_means) = if v.is_main_run() {
                let r = study.result(v, lighting).ok_or_else(|| format!("the main run has no {} image", v.label()))?;
                (r.ratio, r.regions.clone(), None, r.exr.clone(), None, r.mean.clone(), r.pass_means.clone())
            } else {
                let scene_file = derived_scene(&study.scene, v, opts, &rel_dir)?;
                let what = format!("{} {} {}", study.name, lighting.name(), v.label());
                let defines = image_defines(opts, v.bsdf(), lighting);
                let side =
                    render_side(&opts.out.join(&scene_file), opts, defines, &regions, &dir.join("work"), &|k| {
                        progress(&what, k)
                    })?;
                if v == Configuration::OrenNayarFull {
                    keep_passes(opts, &study.name, lighting, v.key(), &side)?;
                }
                let regs = region_ratios(&regions, &side, lambert);
                let mean = side.moments.mean_image();
                let exr = rel_dir.join(format!("{}_{}.exr", lighting.name(), v.key()));
                image_io::write_exr(&opts.out.join(&exr), &mean)?;
                (
                    metrics::luminance_ratio(&side.moments, &lambert.moments),
                    regs,
                    Some(side.seconds),
                    exr,
                    Some(scene_file),
                    mean,
                    side.moments.pass_means,
                )
            };
            images.push((v.tile(), mean.clone()));
            results.push(VariantResult {
                variant: v,
                lighting,
                ratio,
                regions: regs,
                pass_means,
                mean,
                seconds,
                exr,
                scene_file,
            });
        }
        let rels: Vec<Vec<f32>> =
            images.iter().map(|(_, m)| metrics::relative_difference(m, &lambert_img, 1e-4)).collect();
        let range = metrics::heatmap_range(&rels[1..]);
        let tiles: Vec<strip::StripTile> = images.iter().map(|(l, m)| strip::StripTile::from_image(l, m)).collect();
        let diff_tiles: Vec<strip::StripTile> = images
            .iter()
            .zip(&rels)
            .map(|((l, m), rel)| strip::StripTile::from_difference(l, m.width, m.height, rel, range))
            .collect();
        let strip_path = rel_dir.join(format!("strip_{}.png", lighting.name()));
        let diff_path = rel_dir.join(format!("difference_{}.png", lighting.name()));
        strip::write_strip(&opts.out.join(&strip_path), &tiles)?;
        strip::write_strip(&opts.out.join(&diff_path), &diff_tiles)?;
        strips.push((lighting, strip_path, diff_path, range));
    }
    Ok(VariantStudy { scene_name: study.name.clone(), results, strips })
}
