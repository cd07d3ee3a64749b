//! Convergence series (docs/study.md, convergence series): is the paper's Oren–Nayar "glow below the green
//! box" real or a bias? A real property of the model gives a region ratio ON / Lambert that
//! is stable as the sample count grows and the same in both renderers (their 99 % intervals
//! overlap). A bias or noise artefact drifts with spp or differs between renderers.
//!
//! For each region flagged `"convergence": true` in `<scene>.regions.json`, Lambert, Oren–Nayar
//! (qualitative, the default) and Oren–Nayar full are rendered under global illumination at
//! each total spp of the series, with K paired passes per level, by matte and by Mitsuba (the
//! Python environment matte is installed in, [`crate::installation`]). Only the region is rendered: a derived scene ([`super::variant_scene`])
//! sets the film's crop window to the region's pixels at the study's resolution. Mitsuba
//! renders a crop as the same sub-window of the full image (`docs/renderer-semantics.md` §6, crop), so the region
//! keeps the main run's pixels at a fraction of the cost. One difference remains: pixels on
//! the crop's border average only samples inside the crop, which is a filter-width
//! difference at the region's rim. Each level has its own seeds (`seed + 10000·(level + 1) + k`),
//! so the levels are independent.

use super::configuration::{Configuration, SERIES};
use super::metrics;
use super::options::{Lighting, Region, StudyOptions, image_defines};
use super::ratio::Ratio;
use super::variant_scene::{self, Derivation, DerivedProperty};
use crate::validate::crop::{PixelBox, pixel_box};
use crate::validate::passes::{self, Budget, PassPlan, Side};
use matte_render::film::SplatWeights;
use matte_render::load;
use std::path::{Path, PathBuf};

/// One model's region ratio to Lambert at one level in one renderer.
#[derive(Clone, Debug)]
pub struct Point {
    /// Total spp of the level (split over the passes).
    pub spp: u32,
    pub renderer: String,
    pub model: Configuration,
    /// Region luminance ratio to Lambert (paired passes) with its 99 % interval.
    pub ratio: Ratio,
    /// Render seconds of the model's passes.
    pub seconds: f64,
}

pub struct Series {
    pub scene_name: String,
    pub region: String,
    /// Crop window `[x, y, width, height]` in pixels of the `film` size.
    pub crop: [u32; 4],
    pub film: [u32; 2],
    pub passes: u32,
    pub levels: Vec<u32>,
    /// Renderers that ran, in order ("matte", "mitsuba scalar_rgb").
    pub renderers: Vec<String>,
    pub points: Vec<Point>,
    /// Parts that could not run (e.g. no Mitsuba installed), said in the report.
    pub notes: Vec<String>,
}

impl Series {
    pub fn point(&self, model: Configuration, renderer: &str, spp: u32) -> Option<&Point> {
        self.points.iter().find(|p| p.model == model && p.renderer == renderer && p.spp == spp)
    }

    /// The highest level a renderer reached for `model`.
    pub fn best(&self, model: Configuration, renderer: &str) -> Option<&Point> {
        self.points.iter().filter(|p| p.model == model && p.renderer == renderer).max_by_key(|p| p.spp)
    }

    /// Stability over spp: (levels whose interval overlaps the highest level's, levels).
    pub fn stable(&self, model: Configuration, renderer: &str) -> (usize, usize) {
        let Some(best) = self.best(model, renderer) else { return (0, 0) };
        let pts: Vec<&Point> = self.points.iter().filter(|p| p.model == model && p.renderer == renderer).collect();
        (pts.iter().filter(|p| p.ratio.overlaps(best.ratio)).count(), pts.len())
    }

    /// Agreement between the first two renderers: (levels whose intervals overlap, levels
    /// both rendered).
    pub fn agreement(&self, model: Configuration) -> (usize, usize) {
        let [a, b] = match self.renderers.as_slice() {
            [a, b, ..] => [a, b],
            _ => return (0, 0),
        };
        let pairs: Vec<(&Point, &Point)> =
            self.levels.iter().filter_map(|&s| Some((self.point(model, a, s)?, self.point(model, b, s)?))).collect();
        (pairs.iter().filter(|(p, q)| p.ratio.overlaps(q.ratio)).count(), pairs.len())
    }
}

/// Why the series cannot have a Mitsuba side (`None`: it can): no Python with matte_mitsuba,
/// or no Mitsuba in it.
pub fn mitsuba_missing() -> Option<String> {
    crate::installation::mitsuba_side().err()
}

/// Whether the series can have a Mitsuba side.
pub fn mitsuba_available() -> bool {
    mitsuba_missing().is_none()
}

/// Passes a series renders (for the progress bar).
pub fn pass_count(opts: &StudyOptions) -> u64 {
    let renderers = 1 + mitsuba_available() as usize;
    (opts.convergence_spp.len() * SERIES.len() * renderers) as u64 * opts.passes as u64
}

fn slug(s: &str) -> String {
    s.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '_' }).collect()
}

/// Renders the series for `region` of `scene` (named `name`); writes the derived crop scenes
/// into `<out>/<name>/convergence/`. A Mitsuba side that cannot run becomes a note.
pub fn run(
    scene: &Path,
    name: &str,
    region: &Region,
    opts: &StudyOptions,
    progress: &dyn Fn(&str, u32),
) -> Result<Series, String> {
    let rel_dir = PathBuf::from(name).join("convergence");
    let dir = opts.out.join(&rel_dir);
    // The film size with the study's parameters (the crop is in its pixels).
    let film =
        load::load_file(scene, &image_defines(opts, "lambert", Lighting::Global)).map_err(|e| e.to_string())?.film;
    let (w, h) = (film.width(), film.height());
    // The one rounding of a region to pixels, shared with the region means (crop.rs).
    let PixelBox { x0, y0, x1, y1 } = pixel_box(w, h, region.rect);
    let crop = vec![
        DerivedProperty::integer("crop_offset_x", x0 as i64),
        DerivedProperty::integer("crop_offset_y", y0 as i64),
        DerivedProperty::integer("crop_width", (x1 - x0) as i64),
        DerivedProperty::integer("crop_height", (y1 - y0) as i64),
    ];
    let mut files = Vec::new();
    for m in SERIES {
        let file = opts.out.join(&rel_dir).join(format!("{}_{}.xml", slug(&region.name), m.key()));
        let bsdf_properties = m.property().map(|(k, v)| vec![DerivedProperty::string(k, v)]).unwrap_or_default();
        variant_scene::write_derived(
            scene,
            &file,
            &Derivation { bsdf: Some(m.bsdf().into()), bsdf_properties, film_properties: crop.clone() },
        )?;
        files.push(file);
    }
    let mitsuba = format!("mitsuba {}", opts.mitsuba_variant);
    let mut notes = Vec::new();
    let mut active = vec!["matte".to_string()];
    match mitsuba_missing() {
        None => active.push(mitsuba.clone()),
        Some(why) => notes.push(format!(
            "Mitsuba was not run: {why}. The series is matte only, so it cannot show whether the renderers agree."
        )),
    }
    let mut points = Vec::new();
    let mut levels = Vec::new();
    for (i, &nominal) in opts.convergence_spp.iter().enumerate() {
        let per_pass = (nominal / opts.passes).max(1);
        let spp = per_pass * opts.passes;
        levels.push(spp);
        let plan = PassPlan {
            passes: opts.passes,
            spp: Budget::PerPass(per_pass),
            seed: opts.seed + 10_000 * (i as u64 + 1),
            defines: Vec::new(),
            regions: Vec::new(),
        };
        for renderer in active.clone() {
            let mut sides: Vec<Side> = Vec::new();
            for (m, file) in SERIES.iter().zip(&files) {
                let plan = PassPlan { defines: image_defines(opts, m.bsdf(), Lighting::Global), ..plan.clone() };
                let what = format!("{name} convergence {spp} spp {renderer} {}", m.label());
                let side = if renderer == "matte" {
                    passes::rust_side(file, &plan, SplatWeights::of_mitsuba_variant(&opts.mitsuba_variant), &|k| {
                        progress(&what, k)
                    })
                } else {
                    passes::mitsuba_side_installed(file, &opts.mitsuba_variant, &plan, &dir.join("work"), &|k| {
                        progress(&what, k)
                    })
                };
                match side {
                    Ok(s) => sides.push(s),
                    Err(e) if renderer != "matte" => {
                        eprintln!("matte study: warning: the convergence series' Mitsuba side failed: {e}");
                        notes.push(format!(
                            "Mitsuba failed at {spp} spp ({}): {e}. Its later levels were skipped.",
                            m.label()
                        ));
                        active.retain(|r| *r != renderer);
                        break;
                    }
                    Err(e) => return Err(e),
                }
            }
            let Some((lambert, others)) = sides.split_first() else { continue };
            for (m, side) in SERIES[1..].iter().zip(others) {
                // The crop is the region: its image mean is the region mean.
                let ratio = metrics::luminance_ratio(&side.moments, &lambert.moments);
                points.push(Point { spp, renderer: renderer.clone(), model: *m, ratio, seconds: side.seconds });
            }
        }
    }
    let renderers =
        ["matte".to_string(), mitsuba].into_iter().filter(|r| points.iter().any(|p| p.renderer == *r)).collect();
    Ok(Series {
        scene_name: name.to_string(),
        region: region.name.clone(),
        crop: [x0, y0, x1 - x0, y1 - y0],
        film: [w, h],
        passes: opts.passes,
        levels,
        renderers,
        points,
        notes,
    })
}
