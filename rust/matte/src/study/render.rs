//! How the study renders one configuration: K paired passes with the study's seeds and budget
//! in the study's renderer, and the pass images it keeps for the perceptual step
//! ([`super::perceptual`]) in `<out>/<scene>/perceptual_work/`.

use super::options::{Lighting, Region, StudyOptions};
use crate::validate::passes::{self, Budget, PassPlan, Renderer, Side};
use matte_render::film::SplatWeights;
use matte_render::image_io;
use std::path::{Path, PathBuf};

/// K paired passes of `scene` with the study's seeds and budget, in the study's renderer.
pub(crate) fn render_side(
    scene: &Path,
    opts: &StudyOptions,
    defines: Vec<(String, String)>,
    regions: &[Region],
    work: &Path,
    progress: &dyn Fn(u32),
) -> Result<Side, String> {
    let regions = regions.iter().map(|r| r.rect).collect();
    let plan = PassPlan {
        passes: opts.passes,
        spp: Budget::PerPass((opts.spp / opts.passes).max(1)),
        seed: opts.seed,
        defines,
        regions,
    };
    match &opts.renderer {
        Renderer::Matte => passes::rust_side(scene, &plan, SplatWeights::default(), progress),
        Renderer::Mitsuba(variant) => passes::mitsuba_side_installed(scene, variant, &plan, work, progress),
    }
}

/// Where the pass images of a scene wait for the perceptual step, with its job and result
/// (removed after it).
pub(crate) fn kept_passes_dir(opts: &StudyOptions, scene_name: &str) -> PathBuf {
    opts.out.join(scene_name).join("perceptual_work")
}

/// The kept pass image `k` of the configuration `key` in `lighting`, in `dir`.
pub(crate) fn kept_pass_file(dir: &Path, lighting: Lighting, key: &str, k: usize) -> PathBuf {
    dir.join(format!("{}_{key}_{k:02}.exr", lighting.name()))
}

/// Keeps the K pass images of one configuration for the perceptual step (nothing when it is
/// off).
pub fn keep_passes(
    opts: &StudyOptions,
    scene_name: &str,
    lighting: Lighting,
    key: &str,
    side: &Side,
) -> Result<(), String> {
    if !opts.perceptual {
        return Ok(());
    }
    let dir = kept_passes_dir(opts, scene_name);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for (k, img) in side.images.iter().enumerate() {
        image_io::write_exr(&kept_pass_file(&dir, lighting, key, k), img)?;
    }
    Ok(())
}
