//! `matte study`: the seed paper's experiment (Diepstraten & Borgo 2006). Every study scene
//! is rendered with every diffuse model, under global illumination (the scene's own
//! `max_depth`) and under direct lighting only (`max_depth` 2); the report gives per scene and
//! model the image-mean luminance ratio to Lambert with its 99 % confidence interval in both
//! settings (the paper's question: does the difference grow or shrink with global
//! illumination?), where the difference concentrates (edges vs flat regions), labelled strips
//! like the paper's figures and difference heatmaps against Lambert.
//!
//! Two follow-ups answer the rest of the issue: [`variants`] renders the model *variants*
//! (Wolff's normalisation, Oren–Nayar's full model) through derived scenes
//! ([`variant_scene`]), paired with the main run's Lambert; [`convergence`] renders a
//! region's Oren–Nayar / Lambert ratio at increasing spp with both renderers (is the paper's
//! "glow" real or a bias?).
//!
//! The true surfaces ([`configuration::TRUTHS`], simulated microsurfaces as tabulated BRDFs)
//! are rendered beside the models through derived scenes, with the same seeds; [`truth`]
//! restates the paper's question against them: each rough model / its own surface.

pub mod answers;
pub mod configuration;
pub mod convergence;
pub mod font;
pub mod metrics;
pub mod perceptual;
pub mod ratio;
pub mod report;
pub mod strip;
pub mod truth;
pub mod variant_scene;
pub mod variants;

use crate::validate::passes::Renderer;
use crate::validate::passes::{self, Budget, PassPlan, Side};
use configuration::{Configuration, TRUTHS, main_run};
use glam::DVec3;
use matte_render::film::{Image, SplatWeights};
use matte_render::image_io;
use ratio::{Ratio, RegionRatio};
use std::path::{Path, PathBuf};
use variant_scene::{Derivation, DerivedProperty};

/// Global illumination (scene's max_depth) or direct lighting (max_depth 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lighting {
    Global,
    Direct,
}

impl Lighting {
    pub fn name(self) -> &'static str {
        match self {
            Lighting::Global => "global",
            Lighting::Direct => "direct",
        }
    }
}

#[derive(Clone, Debug)]
pub struct StudyOptions {
    pub out: PathBuf,
    pub passes: u32,
    /// Total samples per pixel per image, split over the passes.
    pub spp: u32,
    pub seed: u64,
    /// Film width override (`-D res=…`), if any.
    pub res: Option<u32>,
    pub renderer: Renderer,
    /// Extra `-D` parameters.
    pub defines: Vec<(String, String)>,
    /// Scene names (file stems) whose model variants are rendered; `all` = every scene.
    pub variant_scenes: Vec<String>,
    /// Total spp of each level of the convergence series (empty: no series).
    pub convergence_spp: Vec<u32>,
    /// Mitsuba variant of the convergence series' Mitsuba side.
    pub mitsuba_variant: String,
    /// The simulated surfaces' tables (`matte study` gives the installed package's
    /// `ground_truth/`, [`crate::installation`]).
    pub ground_truth: PathBuf,
    /// The report's BRDF slices (the installed package's `truth_slices/`; `None`: the report
    /// goes without them).
    pub truth_slices: Option<PathBuf>,
    /// Whether the perceptual differences (HDR-FLIP, [`perceptual`]) are computed: keeps the
    /// pass images and renders the noise floor's second Lambert.
    pub perceptual: bool,
}

impl StudyOptions {
    /// Whether the model variants are rendered for the scene named `name`.
    pub fn variants_for(&self, name: &str) -> bool {
        self.variant_scenes.iter().any(|s| s == name || s == "all")
    }
}

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

/// A named image region of a study scene (`<scene>.regions.json` beside the XML), where a
/// paper observation is checked.
#[derive(Clone, Debug)]
pub struct Region {
    pub name: String,
    /// [x0, y0, x1, y1] as fractions of the image.
    pub rect: [f64; 4],
    /// `"convergence": true`: the study renders a convergence series for this region.
    pub convergence: bool,
}

/// The scene's regions, if it has a `.regions.json`.
pub fn load_regions(scene: &Path) -> Result<Vec<Region>, String> {
    /// `<scene>.regions.json` as written.
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct File {
        regions: Vec<Entry>,
    }
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Entry {
        name: String,
        rect: [f64; 4],
        #[serde(default)]
        convergence: bool,
        /// What the region shows, for readers of the file.
        #[serde(default, rename = "why")]
        _why: Option<String>,
    }
    let path = scene.with_extension("regions.json");
    let Ok(text) = std::fs::read_to_string(&path) else { return Ok(Vec::new()) };
    let file: File = serde_json::from_str(&text).map_err(|e| {
        format!(
            "{}: {e} (expected {{\"regions\": [{{\"name\", \"rect\", \"convergence\", \"why\"}}]}})",
            path.display()
        )
    })?;
    file.regions
        .into_iter()
        .map(|r| {
            let [x0, y0, x1, y1] = r.rect;
            if (0.0..=1.0).contains(&x0) && x0 < x1 && x1 <= 1.0 && (0.0..=1.0).contains(&y0) && y0 < y1 && y1 <= 1.0 {
                Ok(Region { name: r.name, rect: r.rect, convergence: r.convergence })
            } else {
                Err(format!(
                    "{}: region \"{}\": rect must be [x0, y0, x1, y1] with 0 ≤ x0 < x1 ≤ 1 and 0 ≤ y0 < y1 ≤ 1, got {:?}",
                    path.display(),
                    r.name,
                    r.rect
                ))
            }
        })
        .collect()
}

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
    pub fn result(&self, model: Configuration, lighting: Lighting) -> Option<&ModelResult> {
        self.results.iter().find(|r| r.model == model && r.lighting == lighting)
    }
    pub fn lambert(&self, lighting: Lighting) -> Option<&Side> {
        self.lambert.iter().find(|(l, _)| *l == lighting).map(|(_, s)| s)
    }
}

/// Everything `matte study` measured, for the report and study.json.
pub struct Study {
    /// "matte" or "mitsuba <variant>".
    pub renderer: String,
    pub passes: u32,
    pub spp: u32,
    pub scenes: Vec<SceneStudy>,
    pub variants: Vec<variants::VariantStudy>,
    /// Per scene with true surfaces: the models against them.
    pub truths: Vec<truth::TruthStudy>,
    pub convergence: Vec<convergence::Series>,
    /// Per scene: HDR-FLIP against Lambert and the surfaces, with noise floors.
    pub perceptual: Vec<perceptual::PerceptualStudy>,
    /// Why a scene has no perceptual differences (one line each).
    pub perceptual_notes: Vec<String>,
}

/// The `-D` parameters of one image: the user's, the model, the lighting and the resolution.
pub(crate) fn image_defines(opts: &StudyOptions, bsdf: &str, lighting: Lighting) -> Vec<(String, String)> {
    let mut defines = opts.defines.clone();
    defines.push(("bsdf".into(), bsdf.into()));
    if lighting == Lighting::Direct {
        defines.push(("max_depth".into(), "2".into()));
    }
    if let Some(r) = opts.res {
        defines.push(("res".into(), r.to_string()));
    }
    defines
}

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

/// Renders one scene with every model in both lighting settings and writes its pictures.
pub fn study_scene(scene: &Path, opts: &StudyOptions, progress: &dyn Fn(&str, u32)) -> Result<SceneStudy, String> {
    let name = scene.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scene".into());
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
        truth::table_source(&opts.ground_truth, file)?;
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
            perceptual::keep_passes(opts, &name, lighting, model.key(), &side)?;
            sides.push((*model, side));
        }
        let what = format!("{name} {} Lambert, other seeds", lighting.name());
        perceptual::render_floor(scene, &name, lighting, &regions, opts, &|k| progress(&what, k))?;
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
        let source = truth::table_source(&opts.ground_truth, file)?;
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
