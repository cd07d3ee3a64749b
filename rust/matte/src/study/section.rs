//! What a part of the study is: a [`Section`] renders and measures (per scene, or per scene
//! after every scene), counts its passes for the progress total, gives its answer sentences,
//! its entry of study.json and its part of report.html. [`Study`] holds what the sections
//! measured; [`super::report::SECTIONS`] is the one list of sections, in order.

use super::convergence::Series;
use super::main_run::{SceneStudy, scene_name};
use super::options::{Region, StudyOptions, load_regions};
use super::perceptual::PerceptualStudy;
use super::truth::TruthStudy;
use super::variants::VariantStudy;
use serde::Serialize;
use serde::ser::SerializeMap;
use std::path::{Path, PathBuf};

/// Everything `matte study` measured, for the report and study.json.
pub struct Study {
    /// What the run was asked to do.
    pub options: StudyOptions,
    /// "matte" or "mitsuba <variant>".
    pub renderer: String,
    pub scenes: Vec<SceneStudy>,
    pub variants: Vec<VariantStudy>,
    /// Per scene with true surfaces: the models against them.
    pub truths: Vec<TruthStudy>,
    pub convergence: Vec<Series>,
    /// Per scene: HDR-FLIP against Lambert and the surfaces, with noise floors.
    pub perceptual: Vec<PerceptualStudy>,
    /// Why a scene has no perceptual differences (one line each).
    pub perceptual_notes: Vec<String>,
}

impl Study {
    /// A study with nothing measured yet.
    pub fn new(options: StudyOptions) -> Study {
        Study {
            renderer: options.renderer_label(),
            options,
            scenes: Vec::new(),
            variants: Vec::new(),
            truths: Vec::new(),
            convergence: Vec::new(),
            perceptual: Vec::new(),
            perceptual_notes: Vec::new(),
        }
    }

    /// The main run of the scene named `name`.
    pub fn scene(&self, name: &str) -> Result<&SceneStudy, String> {
        self.scenes.iter().find(|s| s.name == name).ok_or_else(|| format!("the main run has no scene {name}"))
    }
}

/// A study scene as the sections see it: its file, its name and its regions.
pub struct Scene {
    pub path: PathBuf,
    /// The file stem: the scene's folder in the output and its name in the tables.
    pub name: String,
    /// The named regions of `<scene>.regions.json`.
    pub regions: Vec<Region>,
}

impl Scene {
    /// The scene at `path` with its regions.
    pub fn load(path: &Path) -> Result<Scene, String> {
        Ok(Scene { path: path.to_path_buf(), name: scene_name(path), regions: load_regions(path)? })
    }
}

/// When a section runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// On each scene, after the sections before it in the list.
    PerScene,
    /// On each scene, after every section of [`Stage::PerScene`] ran on every scene.
    AfterScenes,
}

/// Where a run reports its progress.
pub trait Progress {
    /// The number of passes the run renders, before the first.
    fn start(&self, total: u64);
    /// One pass of the part named `what` is rendered.
    fn pass(&self, what: &str);
    /// A step that renders nothing (e.g. the HDR-FLIP evaluations) begins.
    fn step(&self, what: &str);
}

/// No progress shown.
impl Progress for () {
    fn start(&self, _total: u64) {}
    fn pass(&self, _what: &str) {}
    fn step(&self, _what: &str) {}
}

/// The object of study.json while it is written: each section adds its entries.
pub struct JsonObject<'a, 'b> {
    map: &'b mut serde_json::ser::Compound<'a, Vec<u8>, serde_json::ser::PrettyFormatter<'static>>,
}

impl<'a, 'b> JsonObject<'a, 'b> {
    /// Wraps the map of a study.json being written.
    pub(crate) fn new(
        map: &'b mut serde_json::ser::Compound<'a, Vec<u8>, serde_json::ser::PrettyFormatter<'static>>,
    ) -> Self {
        JsonObject { map }
    }

    /// Adds `key: value`.
    pub fn entry<T: Serialize + ?Sized>(&mut self, key: &str, value: &T) -> Result<(), String> {
        self.map.serialize_entry(key, value).map_err(|e| format!("{key}: {e}"))
    }
}

/// One part of the study.
pub trait Section: Sync {
    /// Its name in errors ("variants", "true surfaces").
    fn name(&self) -> &'static str;

    /// When it runs.
    fn stage(&self) -> Stage {
        Stage::PerScene
    }

    /// The passes it renders for `scene` (the progress total).
    fn passes(&self, _scene: &Scene, _opts: &StudyOptions) -> u64 {
        0
    }

    /// Renders and measures `scene`; keeps what it measured in `study`.
    fn run(&self, _scene: &Scene, _study: &mut Study, _progress: &dyn Progress) -> Result<(), String> {
        Ok(())
    }

    /// Its answer sentences.
    fn answers(&self, _study: &Study) -> Vec<String> {
        Vec::new()
    }

    /// Adds its entries to study.json.
    fn json(&self, study: &Study, out: &mut JsonObject) -> Result<(), String>;

    /// A file beside study.json that holds its entries alone (with the run's renderer, passes
    /// and spp).
    fn json_file(&self) -> Option<&'static str> {
        None
    }

    /// Its part of report.html (empty: none); `out` is the report's folder, where it may put
    /// the files it shows.
    fn html(&self, study: &Study, out: &Path) -> Result<String, String>;
}
