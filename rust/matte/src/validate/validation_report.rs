//! The run's outputs: per scene the two mean images (EXR + PNG) and the heatmaps, then
//! `summary.json` (machine-readable) and `report.html` (one page, renders side by side with
//! the maps and the numbers; it links only files the run wrote).

use super::crop::PixelBox;
use super::heatmap;
use super::passes::Side;
use super::scales::Rejection;
use super::stats::ImageComparison;
use super::summary::Provenance;
use super::{SceneResult, write_mean};
use askama::Template;
use matte_render::film::Image;
use matte_render::image_io;
use std::path::{Path, PathBuf};

/// Paths relative to the output folder.
#[derive(Clone, Debug)]
pub struct Files {
    pub matte_exr: PathBuf,
    pub matte_png: PathBuf,
    pub reference_exr: PathBuf,
    pub reference_png: PathBuf,
    pub difference_png: PathBuf,
    pub pvalues_png: PathBuf,
    /// Range of the difference colormap (± this relative difference).
    pub difference_range: f32,
    /// The ranked rejected blocks with their crops (`docs/validation.md#where-it-differs`).
    pub crops: Vec<Crop>,
}

/// Crops of one rejected block: both renderings and the difference map, enlarged.
#[derive(Clone, Debug)]
pub struct Crop {
    pub rejection: Rejection,
    /// The pixels shown (the block with some context).
    pub shown: PixelBox,
    pub matte_png: PathBuf,
    pub reference_png: PathBuf,
    pub difference_png: PathBuf,
}

/// Rejected places shown with crops, most significant first.
pub const CROPS: usize = 8;

/// The pixels shown around a block: at least 24 × 24, centred on it, inside the image.
fn context(b: &PixelBox, w: u32, h: u32) -> PixelBox {
    let grow = |lo: u32, hi: u32, n: u32| {
        let size = (hi - lo + 8).max(24).min(n);
        let centre = (lo + hi) / 2;
        let start = centre.saturating_sub(size / 2).min(n - size);
        (start, start + size)
    };
    let (x0, x1) = grow(b.x0, b.x1, w);
    let (y0, y1) = grow(b.y0, b.y1, h);
    PixelBox { x0, y0, x1, y1 }
}

/// `img` restricted to `b`, enlarged by an integer factor to about 160 pixels.
fn enlarge<T: Copy>(pixels: &[T], w: u32, b: &PixelBox) -> (u32, u32, Vec<T>) {
    let f = (160 / b.width().max(b.height())).max(1);
    let (cw, ch) = (b.width() * f, b.height() * f);
    let v = (0..ch)
        .flat_map(|y| (0..cw).map(move |x| (b.x0 + x / f, b.y0 + y / f)))
        .map(|(x, y)| pixels[(y * w + x) as usize])
        .collect();
    (cw, ch, v)
}

fn write_crops(
    dir: &Path,
    rel_dir: &Path,
    a: &Image,
    b: &Image,
    c: &ImageComparison,
    range: f32,
) -> Result<Vec<Crop>, String> {
    let mut out: Vec<Crop> = Vec::new();
    // One crop per place: a rejection whose block centre is already shown is skipped (the
    // same feature is usually rejected at several scales and on overlapping grids).
    let inside = |b: &PixelBox, x: u32, y: u32| x >= b.x0 && x < b.x1 && y >= b.y0 && y < b.y1;
    for r in c.ranked_rejections() {
        if out.len() == CROPS {
            break;
        }
        let (cx, cy) = ((r.place.x0 + r.place.x1) / 2, (r.place.y0 + r.place.y1) / 2);
        if out.iter().any(|k| inside(&k.shown, cx, cy)) {
            continue;
        }
        let i = out.len();
        let shown = context(&r.place, c.width, c.height);
        let stem = format!("rejected_{i:02}");
        let img = |src: &Image| {
            let (w, h, pixels) = enlarge(&src.pixels, src.width, &shown);
            Image { width: w, height: h, pixels }
        };
        image_io::write_png(&dir.join(format!("{stem}_matte.png")), &img(a))?;
        image_io::write_png(&dir.join(format!("{stem}_reference.png")), &img(b))?;
        let (w, h, rel) = enlarge(&c.rel_diff, c.width, &shown);
        heatmap::write_difference(&dir.join(format!("{stem}_difference.png")), w, h, &rel, range)?;
        out.push(Crop {
            rejection: r.clone(),
            shown,
            matte_png: rel_dir.join(format!("{stem}_matte.png")),
            reference_png: rel_dir.join(format!("{stem}_reference.png")),
            difference_png: rel_dir.join(format!("{stem}_difference.png")),
        });
    }
    Ok(out)
}

pub fn write_scene_files(out: &Path, rel_dir: &Path, a: &Side, b: &Side, c: &ImageComparison) -> Result<Files, String> {
    let dir = out.join(rel_dir);
    write_mean(&dir, "matte", a)?;
    write_mean(&dir, "reference", b)?;
    // Colormap range: the 99th percentile of |relative difference|, at least 2 %.
    let mut abs: Vec<f32> = c.rel_diff.iter().map(|x| x.abs()).filter(|x| x.is_finite()).collect();
    abs.sort_by(f32::total_cmp);
    let p99 = abs.get(((abs.len() as f32 * 0.99) as usize).min(abs.len().saturating_sub(1))).copied().unwrap_or(0.0);
    let range = p99.clamp(0.02, 1.0);
    heatmap::write_difference(&dir.join("difference.png"), c.width, c.height, &c.rel_diff, range)?;
    let p_min: Vec<f32> = c.p.iter().map(|p| p.min_element()).collect();
    heatmap::write_pvalues(&dir.join("pvalues.png"), c.width, c.height, &p_min, c.alpha_pixel)?;
    let crops = write_crops(&dir, rel_dir, &a.moments.mean_image(), &b.moments.mean_image(), c, range)?;
    Ok(Files {
        crops,
        matte_exr: rel_dir.join("matte.exr"),
        matte_png: rel_dir.join("matte.png"),
        reference_exr: rel_dir.join("reference.exr"),
        reference_png: rel_dir.join("reference.png"),
        difference_png: rel_dir.join("difference.png"),
        pvalues_png: rel_dir.join("pvalues.png"),
        difference_range: range,
    })
}

/// report.html: the verdict, the provenance, the overview, then one section per scene.
#[derive(Template)]
#[template(path = "validation_report.html")]
struct ReportHtml<'a> {
    results: &'a [SceneResult],
    all_passed: bool,
    provenance: [(&'static str, String); 5],
}

fn rgb(v: &glam::DVec3) -> String {
    format!("{:.5} {:.5} {:.5}", v.x, v.y, v.z)
}

/// [`percent`] for the template.
fn pct(x: &Option<f64>) -> String {
    percent(*x)
}

pub fn html(results: &[SceneResult], p: &Provenance) -> askama::Result<String> {
    ReportHtml {
        results,
        all_passed: results.iter().all(|r| r.comparison.passed()),
        provenance: [
            ("matte", p.matte.clone()),
            ("Mitsuba", p.mitsuba.clone().unwrap_or_else(|| "not run".into())),
            ("references", p.references.join(", ")),
            ("Python side", p.python.clone().unwrap_or_else(|| "not used".into())),
            ("scenes", p.scenes.clone()),
        ],
    }
    .render()
}

/// The scale that came closest to rejecting: the smallest ratio of its smallest p to its
/// per-test level (below 1 = rejected there), with that ratio.
fn worst_scale(r: &SceneResult) -> Option<(String, f64)> {
    r.comparison.scales.iter().map(|s| (s.scale.label(), s.min_p / s.alpha_test)).min_by(|a, b| a.1.total_cmp(&b.1))
}

/// A detectable relative change as a percentage with two significant digits (changes far
/// below 0.01 % are detectable where both renderers are exact, e.g. directly seen emitters);
/// `None`: not detectable by any change tried.
pub fn percent(x: Option<f64>) -> String {
    match x {
        Some(d) => {
            let p = d * 100.0;
            let decimals = if p > 0.0 { (1.0 - p.log10().floor()).clamp(0.0, 12.0) as usize } else { 2 };
            format!("{p:.decimals$} %")
        }
        None => "more than 30 %".into(),
    }
}

/// summary.json, report.html and the colour bars in `out`.
pub fn write_run(out: &Path, results: &[SceneResult], provenance: &Provenance) -> Result<(), String> {
    heatmap::write_colorbars(&out.join("colorbar_difference.png"), &out.join("colorbar_pvalues.png"))?;
    let json = super::summary::Summary::new(results, provenance).to_json();
    std::fs::write(out.join("summary.json"), json).map_err(|e| e.to_string())?;
    let page = html(results, provenance).map_err(|e| format!("report.html: {e}"))?;
    std::fs::write(out.join("report.html"), page).map_err(|e| e.to_string())
}
