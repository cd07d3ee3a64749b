//! The main run: every study scene rendered with every model of
//! [`main_run`](super::configuration::main_run) and every true surface, under global
//! illumination and under direct lighting only, with the same seeds; per model the luminance
//! ratio to Lambert with its 99 % interval, the edge/flat concentration of the difference,
//! the named regions' ratios, the strips and the heatmap strips.

use super::configuration::{Configuration, TRUTHS, main_run};
use super::options::{Lighting, Region, StudyOptions, image_defines, load_regions};
use super::ratio::{Ratio, RegionRatio};
use super::render::{keep_passes, render_side};
use super::variant_scene::{self, Derivation, DerivedProperty};
use super::{metrics, strip};
use crate::validate::passes::Side;
use glam::DVec3;
use matte_render::film::Image;
use matte_render::image_io;
use std::path::{Path, PathBuf};

/// One model in one lighting setting.
pub struct ModelResult {
    pub model: Configuration,
    pub lighting: Lighting,
    pub mean: Image,
    /// Per-pass image means, in seed order (for ratios paired with other configurations).
    pub pass_means: Vec<DVec3>,
    /// Luminance ratio to Lambert (same lighting) with its 99 % interval.
    pub ratio: Ratio,
    /// Mean |relative difference| to Lambert on edge pixels and on flat pixels.
    pub edge_flat: (f64, f64),
    pub seconds: f64,
    pub exr: PathBuf,
    /// Per named region of the scene: luminance ratio to Lambert.
    pub regions: Vec<RegionRatio>,
}

/// One scene's main run.
pub struct SceneStudy {
    pub scene: PathBuf,
    pub name: String,
    pub results: Vec<ModelResult>,
    /// Strip and heatmap strip per lighting, relative to the output folder.
    pub strips: Vec<(Lighting, PathBuf, PathBuf)>,
    /// Colour-scale half-range (relative difference) of each lighting's heatmap strip.
    pub difference_ranges: Vec<(Lighting, f32)>,
    /// Lambert's passes per lighting: the variants are paired with them.
    pub lambert: Vec<(Lighting, Side)>,
    /// What could not be rendered, and why (e.g. a scene whose `$bsdf` is in an included file
    /// cannot take a true surface's table).
    pub notes: Vec<String>,
}

impl SceneStudy {
    /// The result of `model` in `lighting`, if it was rendered.
    pub fn result(&self, model: Configuration, lighting: Lighting) -> Option<&ModelResult> {
        self.results.iter().find(|r| r.model == model && r.lighting == lighting)
    }

    /// Lambert's passes in `lighting`.
    pub fn lambert(&self, lighting: Lighting) -> Option<&Side> {
        self.lambert.iter().find(|(l, _)| *l == lighting).map(|(_, s)| s)
    }

    /// The colour-scale half-range of `lighting`'s heatmap strip (NaN when it has none).
    pub fn difference_range(&self, lighting: Lighting) -> f32 {
        self.difference_ranges.iter().find(|(x, _)| *x == lighting).map_or(f32::NAN, |r| r.1)
    }

    /// A result's per-pass ratios to Lambert's passes in the same lighting.
    pub fn pass_ratios(&self, r: &ModelResult) -> Vec<f64> {
        self.lambert(r.lighting).map(|l| metrics::pass_ratios(&r.pass_means, &l.moments.pass_means)).unwrap_or_default()
    }

    /// Whether the scene is lit directly only: its own max_depth is 2, so Lambert's passes
    /// are the same in both settings (up to the order in which tiles reach the film).
    pub fn direct_only(&self) -> bool {
        match (self.lambert(Lighting::Global), self.lambert(Lighting::Direct)) {
            (Some(g), Some(d)) => g
                .moments
                .pass_means
                .iter()
                .zip(&d.moments.pass_means)
                .all(|(a, b)| (*a - *b).abs().max_element() <= 1e-9 * a.abs().max_element().max(1e-30)),
            _ => false,
        }
    }

    /// The paper's question for `model`: Δ = |r_global − 1| − |r_direct − 1| of its ratios to
    /// Lambert with its 99 % interval, paired per seed ([`metrics::growth`]).
    pub fn growth(&self, model: Configuration) -> Option<Ratio> {
        let g = self.result(model, Lighting::Global)?;
        let d = self.result(model, Lighting::Direct)?;
        self.lambert(Lighting::Global).and(self.lambert(Lighting::Direct))?;
        Some(metrics::growth(&self.pass_ratios(g), &self.pass_ratios(d)))
    }
}

/// A true surface's table file: `<folder>/<file>` (the installed package's `ground_truth/`).
pub fn table_source(folder: &Path, file: &str) -> Result<PathBuf, String> {
    let path = folder.join(file);
    if path.is_file() { Ok(path) } else { Err(format!("ground-truth table {file} not found ({})", path.display())) }
}

/// The file stem of a scene, its name in the study's folders and tables.
pub fn scene_name(scene: &Path) -> String {
    scene.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scene".into())
}

/// Renders one scene with every model in both lighting settings and writes its pictures.
pub fn study_scene(scene: &Path, opts: &StudyOptions, progress: &dyn Fn(&str, u32)) -> Result<SceneStudy, String> {
    let name = scene_name(scene);
    let dir = opts.out.join(&name);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut results = Vec::new();
    let mut strips = Vec::new();
    let mut ranges = Vec::new();
    let mut lamberts = Vec::new();
    let regions = load_regions(scene)?;
    let mut notes = Vec::new();
    // The models on the scene itself, then the true surfaces on their derived scenes.
    let mut configurations: Vec<(Configuration, PathBuf)> =
        main_run().into_iter().map(|m| (m, scene.to_path_buf())).collect();
    let truth_dir = PathBuf::from(&name).join("truth");
    // A missing table is an error; a scene that cannot be derived only loses the surfaces.
    for file in TRUTHS.iter().filter_map(|t| t.table()) {
        table_source(&opts.ground_truth, file)?;
    }
    let truths: Result<Vec<_>, String> =
        TRUTHS.iter().map(|t| derived_scene(scene, *t, opts, &truth_dir).map(|f| (*t, opts.out.join(f)))).collect();
    match truths {
        Ok(t) => configurations.extend(t),
        Err(e) => notes.push(format!("The true surfaces were not rendered: {e}")),
    }
    for lighting in [Lighting::Global, Lighting::Direct] {
        let mut sides: Vec<(Configuration, Side)> = Vec::new();
        for (model, file) in &configurations {
            let defines = image_defines(opts, model.bsdf(), lighting);
            let what = format!("{name} {} {}", lighting.name(), model.label());
            let side = render_side(file, opts, defines, &regions, &dir.join("work"), &|k| progress(&what, k))?;
            keep_passes(opts, &name, lighting, model.key(), &side)?;
            sides.push((*model, side));
        }
        let lambert = &sides[0].1;
        let lambert_img = lambert.moments.mean_image();
        let edges = metrics::edge_mask(&lambert_img, 0.1);
        let means: Vec<Image> = sides.iter().map(|(_, side)| side.moments.mean_image()).collect();
        let rels: Vec<Vec<f32>> = means.iter().map(|m| metrics::relative_difference(m, &lambert_img, 1e-4)).collect();
        let range = metrics::heatmap_range(&rels[1..]);
        ranges.push((lighting, range));
        let mut tiles = Vec::new();
        let mut diff_tiles = Vec::new();
        for (((model, side), mean), rel) in sides.iter().zip(means).zip(&rels) {
            let exr = PathBuf::from(&name).join(format!("{}_{}.exr", lighting.name(), model.key()));
            image_io::write_exr(&opts.out.join(&exr), &mean)?;
            tiles.push(strip::StripTile::from_image(model.tile(), &mean));
            diff_tiles.push(strip::StripTile::from_difference(model.tile(), mean.width, mean.height, rel, range));
            results.push(ModelResult {
                model: *model,
                lighting,
                pass_means: side.moments.pass_means.clone(),
                ratio: metrics::luminance_ratio(&side.moments, &lambert.moments),
                edge_flat: metrics::edge_vs_flat(rel, &edges),
                seconds: side.seconds,
                mean,
                exr,
                regions: region_ratios(&regions, side, lambert),
            });
        }
        let strip_path = PathBuf::from(&name).join(format!("strip_{}.png", lighting.name()));
        let diff_path = PathBuf::from(&name).join(format!("difference_{}.png", lighting.name()));
        strip::write_strip(&opts.out.join(&strip_path), &tiles)?;
        strip::write_strip(&opts.out.join(&diff_path), &diff_tiles)?;
        strips.push((lighting, strip_path, diff_path));
        if let Some((_, side)) = sides.into_iter().next() {
            lamberts.push((lighting, side));
        }
    }
    Ok(SceneStudy {
        scene: scene.to_path_buf(),
        name,
        results,
        strips,
        difference_ranges: ranges,
        lambert: lamberts,
        notes,
    })
}

/// The derived scene of a configuration that is not the plugin's defaults, written to
/// `<out>/<rel_dir>/<key>.xml` (path returned relative to the output folder): its property
/// in every `<bsdf type="$bsdf">`, or for a true surface its table, copied beside the derived
/// scene and named by its absolute path (both renderers load it from there).
pub fn derived_scene(scene: &Path, c: Configuration, opts: &StudyOptions, rel_dir: &Path) -> Result<PathBuf, String> {
    let dir = opts.out.join(rel_dir);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut properties: Vec<DerivedProperty> =
        c.property().map(|(k, x)| vec![DerivedProperty::string(k, x)]).unwrap_or_default();
    if let Some(file) = c.table() {
        let source = table_source(&opts.ground_truth, file)?;
        let copy = std::path::absolute(dir.join(file)).map_err(|e| format!("{}: {e}", dir.display()))?;
        std::fs::copy(&source, &copy).map_err(|e| format!("{} → {}: {e}", source.display(), copy.display()))?;
        properties.push(DerivedProperty::string("filename", &copy.to_string_lossy()));
    }
    let scene_file = rel_dir.join(format!("{}.xml", c.key()));
    let derivation = Derivation { bsdf: Some(c.bsdf().into()), bsdf_properties: properties, ..Default::default() };
    variant_scene::write_derived(scene, &opts.out.join(&scene_file), &derivation)?;
    Ok(scene_file)
}

/// Each region's luminance ratio of `side` to Lambert's passes (paired by pass).
pub(crate) fn region_ratios(regions: &[Region], side: &Side, lambert: &Side) -> Vec<RegionRatio> {
    regions
        .iter()
        .enumerate()
        .map(|(i, r)| RegionRatio {
            name: r.name.clone(),
            ratio: metrics::paired_luminance_ratio(&side.region_pass_means[i], &lambert.region_pass_means[i]),
        })
        .collect()
}

/// The study scenes: every `*.xml` in the bundled scenes' `study/` folder (the installed
/// matte_mitsuba package's, [`crate::installation`]).
pub fn study_scenes() -> Result<Vec<PathBuf>, String> {
    crate::validate::bundled_scenes(&crate::installation::scenes_dir()?.join("study"))
}
