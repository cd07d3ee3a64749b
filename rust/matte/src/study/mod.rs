//! `matte study`: the seed paper's experiment (Diepstraten & Borgo 2006). Every study scene
//! is rendered with every diffuse model, under global illumination (the scene's own
//! `max_depth`) and under direct lighting only (`max_depth` 2); the report gives per scene and
//! model the image-mean luminance ratio to Lambert with its 99 % confidence interval in both
//! settings (the paper's question: does the difference grow or shrink with global
//! illumination?), where the difference concentrates (edges vs flat regions), labelled strips
//! like the paper's figures and difference heatmaps against Lambert.
//!
//! Two follow-ups: [`variants`] renders the model *variants*
//! (Wolff's normalisation, Oren–Nayar's full model) through derived scenes
//! ([`variant_scene`]), paired with the main run's Lambert; [`convergence`] renders a
//! region's Oren–Nayar / Lambert ratio at increasing spp with both renderers (is the paper's
//! "glow" real or a bias?).
//!
//! The true surfaces ([`configuration::TRUTHS`], simulated microsurfaces as tabulated BRDFs)
//! are rendered beside the models through derived scenes, with the same seeds; [`truth`]
//! restates the paper's question against them: each rough model / its own surface.
//! [`perceptual`] asks whether the differences are visible (HDR-FLIP).
//!
//! [`run`] runs the sections of [`report::SECTIONS`] ([`section::Section`]: the main run, the
//! variants, the true surfaces, the perceptual differences, the convergence series) on every
//! scene, in that order; [`report`] writes what they measured as study.json and report.html.

pub mod answers;
pub mod configuration;
pub mod convergence;
pub mod font;
pub mod main_run;
pub mod metrics;
pub mod options;
pub mod perceptual;
pub mod ratio;
pub mod render;
pub mod report;
pub mod section;
pub mod strip;
pub mod truth;
pub mod variant_scene;
pub mod variants;

pub use main_run::{ModelResult, SceneStudy, derived_scene, study_scene, study_scenes};
pub use options::{Lighting, Region, StudyOptions, load_regions};
pub use section::{Progress, Scene, Section, Stage, Study};

use std::path::PathBuf;

/// The passes a run of `scenes` renders, over every section.
pub fn pass_total(scenes: &[Scene], opts: &StudyOptions) -> u64 {
    scenes.iter().flat_map(|scene| report::SECTIONS.iter().map(move |s| s.passes(scene, opts))).sum()
}

/// Runs every section of [`report::SECTIONS`] on `scenes`: first the sections that run per
/// scene, scene by scene, then those that run after every scene. An error names the scene and
/// the section.
pub fn run(scenes: &[PathBuf], opts: &StudyOptions, progress: &dyn Progress) -> Result<Study, String> {
    if scenes.is_empty() {
        return Err("no study scenes".into());
    }
    std::fs::create_dir_all(&opts.out).map_err(|e| format!("{}: {e}", opts.out.display()))?;
    let scenes: Vec<Scene> =
        scenes.iter().map(|p| Scene::load(p).map_err(|e| format!("{}: {e}", p.display()))).collect::<Result<_, _>>()?;
    progress.start(pass_total(&scenes, opts));
    let mut study = Study::new(opts.clone());
    for stage in [Stage::PerScene, Stage::AfterScenes] {
        for scene in &scenes {
            for section in report::SECTIONS.iter().filter(|s| s.stage() == stage) {
                section
                    .run(scene, &mut study, progress)
                    .map_err(|e| format!("{}: {}: {e}", scene.path.display(), section.name()))?;
            }
        }
    }
    Ok(study)
}
