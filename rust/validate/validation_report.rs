//! The run's outputs: per scene the two mean images (EXR + PNG) and the heatmaps, then
//! `summary.json` (machine-readable) and `report.html` (one page, renders side by side with
//! the maps and the numbers; it links only files the run wrote).

use super::crop::PixelBox;
use super::heatmap;
use super::passes::Side;
use super::power::Calibration;
use super::predicted_power::Prediction;
use super::scales::Rejection;
use super::stats::ImageComparison;
use super::summary::Provenance;
use super::{SceneResult, write_mean};
use crate::markup::escape;
use matte_render::film::Image;
use matte_render::image_io;
use std::fmt::Write as _;
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

fn rgb(v: glam::DVec3) -> String {
    format!("{:.5} {:.5} {:.5}", v.x, v.y, v.z)
}

pub fn html(results: &[SceneResult], provenance: &Provenance) -> String {
    let mut h = String::new();
    let all = results.iter().all(|r| r.comparison.passed());
    let _ = write!(
        h,
        r#"<!doctype html><html><head><meta charset="utf-8"><title>matte validate</title><style>
body{{font-family:system-ui,sans-serif;margin:24px;color:#222}} h1{{margin-bottom:4px}}
.scene{{border-top:1px solid #ccc;padding:12px 0}} .imgs{{display:flex;gap:12px;flex-wrap:wrap}}
figure{{margin:0}} figcaption{{font-size:13px;color:#555}} img.r{{width:256px;image-rendering:pixelated;border:1px solid #ddd}}
table{{border-collapse:collapse;font-size:13px;margin-top:8px}} td,th{{padding:2px 10px;text-align:left;border-bottom:1px solid #eee}}
.pass{{color:#17803d;font-weight:bold}} .fail{{color:#c0262d;font-weight:bold}} .bar{{width:256px;height:12px;display:block}} table.provenance{{margin:4px 0 18px}} table.provenance th{{color:#555;font-weight:normal}}
</style></head><body><h1>matte validate</h1><p>Overall: <span class="{}">{}</span> — {} scene(s). Welch t-tests between the two renderers' per-pass means
at several scales: pixels, blocks of 4², 16² and 64² pixels (four half-offset grids each) and the whole image, per channel;
Šidák-corrected within a scale, Bonferroni over the scales, so the whole family is held at α. A scene passes when no
scale rejects anything (docs/validation.md).</p>"#,
        if all { "pass" } else { "fail" },
        if all { "PASS" } else { "FAIL" },
        results.len()
    );
    h.push_str(&provenance_html(provenance));
    h.push_str(&summary_table(results));
    for (i, r) in results.iter().enumerate() {
        let c = &r.comparison;
        let f = &r.files;
        let p = |p: &PathBuf| escape(&p.display().to_string());
        let _ = write!(
            h,
            r#"<div class="scene" id="scene-{i}"><h2>{name} <small>vs {reference}</small> <span class="{cls}">{verdict}</span></h2><p>{predicted}</p><p>{power}</p>
<div class="imgs">
<figure><img class="r" src="{mp}"><figcaption>matte (<a href="{me}">EXR</a>)</figcaption></figure>
<figure><img class="r" src="{rp}"><figcaption>{reference} (<a href="{re}">EXR</a>)</figcaption></figure>
<figure><img class="r" src="{dp}"><figcaption>(matte − ref) / ref<img class="bar" src="colorbar_difference.png">−{range:.1}% … 0 … +{range:.1}%</figcaption></figure>
<figure><img class="r" src="{pp}"><figcaption>per-pixel test: −log₁₀ p<img class="bar" src="colorbar_pvalues.png">0 … {thr:.1} (Šidák threshold); magenta = rejected</figcaption></figure>
</div><table>
<tr><th>rejected pixels</th><td>{rej} of {n} ({frac:.4}%) at α<sub>pixel</sub> = {ap:.2e} (family α = {alpha})</td></tr>
<tr><th>uncorrected rejection rate</th><td>{unc:.4}% of channel tests at p &lt; {alpha} (≈ {alpha_pct}% expected when equal)</td></tr>
<tr><th>image mean, matte</th><td>{ma}</td></tr><tr><th>image mean, {reference}</th><td>{mb}</td></tr>
<tr><th>difference ± 99% CI</th><td>{d} ± {ci}</td></tr><tr><th>global p (R G B)</th><td>{gp}</td></tr>
<tr><th>passes × spp</th><td>{passes} × {spp} per renderer</td></tr>
<tr><th>render time</th><td>matte {ta:.2} s, {reference} {tb:.2} s</td></tr>
</table>{extra}</div>"#,
            predicted = predicted_power_html(&r.predicted_power),
            power = power_html(r.power.as_ref()),
            extra = scales_html(r) + &crops_html(r),
            name = escape(&r.name),
            reference = escape(&r.reference),
            cls = if c.passed() { "pass" } else { "fail" },
            verdict = if c.passed() { "PASS" } else { "FAIL" },
            mp = p(&f.matte_png),
            me = p(&f.matte_exr),
            rp = p(&f.reference_png),
            re = p(&f.reference_exr),
            dp = p(&f.difference_png),
            pp = p(&f.pvalues_png),
            range = f.difference_range * 100.0,
            thr = -c.alpha_pixel.log10(),
            rej = c.rejected_pixels,
            n = c.width as u64 * c.height as u64,
            frac = c.rejected_fraction() * 100.0,
            ap = c.alpha_pixel,
            alpha = c.alpha,
            unc = c.uncorrected_rejection_rate * 100.0,
            alpha_pct = c.alpha * 100.0,
            ma = rgb(c.global.mean_a),
            mb = rgb(c.global.mean_b),
            d = rgb(c.global.diff),
            ci = rgb(c.global.ci99),
            gp = format_args!("{:.3} {:.3} {:.3}", c.global.p.x, c.global.p.y, c.global.p.z),
            passes = r.passes,
            spp = r.spp_per_pass,
            ta = r.seconds_matte,
            tb = r.seconds_reference,
        );
    }
    h.push_str("</body></html>\n");
    h
}

/// The scale that came closest to rejecting: the smallest ratio of its smallest p to its
/// per-test level (below 1 = rejected there), with that ratio.
fn worst_scale(r: &SceneResult) -> Option<(String, f64)> {
    r.comparison.scales.iter().map(|s| (s.scale.label(), s.min_p / s.alpha_test)).min_by(|a, b| a.1.total_cmp(&b.1))
}

/// The overview on the first screen: one row per scene, linking to its section.
fn summary_table(results: &[SceneResult]) -> String {
    let mut h = String::from(
        "<table class=\"summary\"><tr><th>scene</th><th>reference</th><th>verdict</th>\
         <th>worst scale (smallest p ÷ its level)</th><th>detectable uniform change</th>\
         <th>detectable 16×16 patch change</th><th>time matte / reference</th></tr>",
    );
    for (i, r) in results.iter().enumerate() {
        let passed = r.comparison.passed();
        let worst = worst_scale(r).map_or("–".into(), |(label, ratio)| format!("{label} ({ratio:.3})"));
        // Measured by injection where the run calibrated power, else predicted.
        let (uniform, patch) = match &r.power {
            Some(p) => (format!("{} (measured)", percent(p.uniform.detected)), percent(p.patch.detected)),
            None => (percent(r.predicted_power.uniform), percent(r.predicted_power.patch)),
        };
        let _ = write!(
            h,
            "<tr><td><a href=\"#scene-{i}\">{}</a></td><td>{}</td><td class=\"{}\">{}</td><td>{worst}</td>\
             <td>{uniform}</td><td>{patch}</td><td>{:.2} s / {:.2} s</td></tr>",
            escape(&r.name),
            escape(&r.reference),
            if passed { "pass" } else { "fail" },
            if passed { "PASS" } else { "FAIL" },
            r.seconds_matte,
            r.seconds_reference,
        );
    }
    h + "</table>"
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

fn predicted_power_html(p: &Prediction) -> String {
    format!(
        "Predicted from this run's own variances (a lower bound on power; docs/validation.md#power): \
         80 % power for a uniform relative change of <b>{}</b>, or of <b>{}</b> confined to the 16×16 patch at ({}, {}).",
        percent(p.uniform),
        percent(p.patch),
        p.patch_place.x0,
        p.patch_place.y0,
    )
}

fn power_html(p: Option<&Calibration>) -> String {
    let Some(p) = p else {
        return "Not measured by injection (run with <code>--power</code>).".into();
    };
    let d = percent;
    // Injection measures power on top of the existing difference: meaningless when that
    // difference alone is already rejected in most replicates.
    let note = if p.unchanged.fraction() > 0.5 {
        " (The unchanged comparison already fails in most replicates, so these numbers say nothing about power.)"
    } else {
        ""
    };
    format!(
        "This budget detects, with 80 % power (measured by injection over {} replicate pairs): a uniform relative change \
         of <b>{}</b>, or a change of <b>{}</b> confined to the 16×16 patch at ({}, {}). Identical inputs rejected in \
         {}/{} matte and {}/{} reference replicate pairs; the unchanged comparison in {}/{} replicates.{}",
        p.replicates,
        d(p.uniform.detected),
        d(p.patch.detected),
        p.patch_place.x0,
        p.patch_place.y0,
        p.identical_matte.rejected,
        p.identical_matte.pairs,
        p.identical_reference.rejected,
        p.identical_reference.pairs,
        p.unchanged.rejected,
        p.unchanged.pairs,
        note
    )
}

fn scales_html(r: &SceneResult) -> String {
    let mut h = String::from(
        "<table><tr><th>scale</th><th>blocks</th><th>level per test</th><th>rejected</th><th>smallest p</th></tr>",
    );
    for s in &r.comparison.scales {
        let _ = write!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{:.2e}</td><td class=\"{}\">{}</td><td>{:.2e}</td></tr>",
            s.scale.label(),
            s.blocks,
            s.alpha_test,
            if s.rejected > 0 { "fail" } else { "pass" },
            s.rejected,
            s.min_p
        );
    }
    h + "</table>"
}

fn crops_html(r: &SceneResult) -> String {
    if r.files.crops.is_empty() {
        return String::new();
    }
    let mut h = String::from("<h3>Where it differs (rejected blocks, most significant first)</h3>");
    for (i, c) in r.files.crops.iter().enumerate() {
        let q = &c.rejection;
        let p = |p: &PathBuf| escape(&p.display().to_string());
        let _ = write!(
            h,
            r#"<p>{n}. {scale} at x {x0}–{x1}, y {y0}–{y1}: p = {pv:.2e}, relative difference {rel:+.2} % (crops show x {sx0}–{sx1}, y {sy0}–{sy1})</p>
<div class="imgs"><figure><img src="{m}"><figcaption>matte</figcaption></figure><figure><img src="{rf}"><figcaption>{reference}</figcaption></figure>
<figure><img src="{d}"><figcaption>(matte − ref) / ref, ±{range:.1} %</figcaption></figure></div>"#,
            n = i + 1,
            scale = q.scale.label(),
            x0 = q.place.x0,
            x1 = q.place.x1 - 1,
            y0 = q.place.y0,
            y1 = q.place.y1 - 1,
            pv = q.p,
            rel = q.rel_diff * 100.0,
            sx0 = c.shown.x0,
            sx1 = c.shown.x1 - 1,
            sy0 = c.shown.y0,
            sy1 = c.shown.y1 - 1,
            m = p(&c.matte_png),
            rf = p(&c.reference_png),
            d = p(&c.difference_png),
            reference = escape(&r.reference),
            range = r.files.difference_range * 100.0,
        );
    }
    h
}

/// The run's provenance as a small table: matte, Mitsuba, the references, the Python side, the scenes.
fn provenance_html(p: &Provenance) -> String {
    let rows = [
        ("matte", p.matte.clone()),
        ("Mitsuba", p.mitsuba.clone().unwrap_or_else(|| "not run".into())),
        ("references", p.references.join(", ")),
        ("Python side", p.python.clone().unwrap_or_else(|| "not used".into())),
        ("scenes", p.scenes.clone()),
    ];
    let mut h = String::from(r#"<table class="provenance">"#);
    for (k, v) in rows {
        let _ = write!(h, "<tr><th>{k}</th><td>{}</td></tr>", escape(&v));
    }
    h.push_str("</table>");
    h
}

/// summary.json, report.html and the colour bars in `out`.
pub fn write_run(out: &Path, results: &[SceneResult], provenance: &Provenance) -> Result<(), String> {
    heatmap::write_colorbars(&out.join("colorbar_difference.png"), &out.join("colorbar_pvalues.png"))?;
    let json = super::summary::Summary::new(results, provenance).to_json();
    std::fs::write(out.join("summary.json"), json).map_err(|e| e.to_string())?;
    std::fs::write(out.join("report.html"), html(results, provenance)).map_err(|e| e.to_string())
}
