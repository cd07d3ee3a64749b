//! What a study run is asked to do ([`StudyOptions`]), its two lighting settings and the
//! image regions a scene names for the paper's observations.

use crate::validate::passes::Renderer;
use std::path::{Path, PathBuf};

/// Global illumination (scene's max_depth) or direct lighting (max_depth 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lighting {
    Global,
    Direct,
}

impl Lighting {
    /// The setting's name in file names, JSON and the report: `global` or `direct`.
    pub fn name(self) -> &'static str {
        match self {
            Lighting::Global => "global",
            Lighting::Direct => "direct",
        }
    }
}

/// Everything a study run is asked to do.
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
    /// Whether the perceptual differences (HDR-FLIP, [`super::perceptual`]) are computed:
    /// keeps the pass images and renders the noise floor's second Lambert.
    pub perceptual: bool,
}

impl StudyOptions {
    /// Whether the model variants are rendered for the scene named `name`.
    pub fn variants_for(&self, name: &str) -> bool {
        self.variant_scenes.iter().any(|s| s == name || s == "all")
    }

    /// The renderer as the report names it: "matte" or "mitsuba <variant>".
    pub fn renderer_label(&self) -> String {
        match &self.renderer {
            Renderer::Matte => "matte".to_string(),
            Renderer::Mitsuba(v) => format!("mitsuba {v}"),
        }
    }
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
