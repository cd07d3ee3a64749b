//! The run's outputs: per scene the two mean images (EXR + PNG) and the heatmaps, then
//! `summary.json` (machine-readable) and `report.html` (one page, renders side by side with
//! the maps and the numbers; it links only files the run wrote).

use super::heatmap;
use super::passes::Side;
use super::stats::Comparison;
use super::{SceneResult, write_mean};
use serde_json::json;
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
}

pub fn write_scene_files(out: &Path, rel_dir: &Path, a: &Side, b: &Side, c: &Comparison) -> Result<Files, String> {
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
    Ok(Files {
        matte_exr: rel_dir.join("matte.exr"),
        matte_png: rel_dir.join("matte.png"),
        reference_exr: rel_dir.join("reference.exr"),
        reference_png: rel_dir.join("reference.png"),
        difference_png: rel_dir.join("difference.png"),
        pvalues_png: rel_dir.join("pvalues.png"),
        difference_range: range,
    })
}

fn v3(v: glam::DVec3) -> serde_json::Value {
    json!([v.x, v.y, v.z])
}

pub fn summary_json(results: &[SceneResult]) -> serde_json::Value {
    let scenes: Vec<_> = results
        .iter()
        .map(|r| {
            let c = &r.comparison;
            json!({
                "scene": r.scene.display().to_string(),
                "reference": r.reference,
                "passed": c.passed(),
                "width": c.width, "height": c.height,
                "passes": r.passes, "spp_per_pass": r.spp_per_pass,
                "alpha": c.alpha, "alpha_pixel": c.alpha_pixel,
                "rejected_pixels": c.rejected_pixels,
                "rejected_fraction": c.rejected_fraction(),
                "uncorrected_rejection_rate": c.uncorrected_rejection_rate,
                "global": {
                    "mean_matte": v3(c.global.mean_a), "mean_reference": v3(c.global.mean_b),
                    "difference": v3(c.global.diff), "ci99_half_width": v3(c.global.ci99),
                    "p": v3(c.global.p), "rejected": c.global.rejected,
                },
                "seconds_matte": r.seconds_matte, "seconds_reference": r.seconds_reference,
                "files": {
                    "matte_exr": r.files.matte_exr, "matte_png": r.files.matte_png,
                    "reference_exr": r.files.reference_exr, "reference_png": r.files.reference_png,
                    "difference_png": r.files.difference_png, "pvalues_png": r.files.pvalues_png,
                    "difference_range": r.files.difference_range,
                },
            })
        })
        .collect();
    json!({ "passed": results.iter().all(|r| r.comparison.passed()), "scenes": scenes })
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

fn rgb(v: glam::DVec3) -> String {
    format!("{:.5} {:.5} {:.5}", v.x, v.y, v.z)
}

pub fn html(results: &[SceneResult]) -> String {
    let mut h = String::new();
    let all = results.iter().all(|r| r.comparison.passed());
    let _ = write!(
        h,
        r#"<!doctype html><html><head><meta charset="utf-8"><title>matte validate</title><style>
body{{font-family:system-ui,sans-serif;margin:24px;color:#222}} h1{{margin-bottom:4px}}
.scene{{border-top:1px solid #ccc;padding:12px 0}} .imgs{{display:flex;gap:12px;flex-wrap:wrap}}
figure{{margin:0}} figcaption{{font-size:13px;color:#555}} img.r{{width:256px;image-rendering:pixelated;border:1px solid #ddd}}
table{{border-collapse:collapse;font-size:13px;margin-top:8px}} td,th{{padding:2px 10px;text-align:left;border-bottom:1px solid #eee}}
.pass{{color:#17803d;font-weight:bold}} .fail{{color:#c0262d;font-weight:bold}} .bar{{width:256px;height:12px;display:block}}
</style></head><body><h1>matte validate</h1><p>Overall: <span class="{}">{}</span> — {} scene(s). Per pixel and channel:
Welch t-test between the two renderers' pass means, Šidák-corrected over all pixels and channels; globally: Welch test of
the image mean per channel (Bonferroni over channels). A scene passes when no pixel and no channel mean is rejected.</p>"#,
        if all { "pass" } else { "fail" },
        if all { "PASS" } else { "FAIL" },
        results.len()
    );
    for r in results {
        let c = &r.comparison;
        let f = &r.files;
        let p = |p: &PathBuf| esc(&p.display().to_string());
        let _ = write!(
            h,
            r#"<div class="scene"><h2>{name} <small>vs {reference}</small> <span class="{cls}">{verdict}</span></h2>
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
</table></div>"#,
            name = esc(&r.name),
            reference = esc(&r.reference),
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

/// summary.json, report.html and the colour bars in `out`.
pub fn write_run(out: &Path, results: &[SceneResult]) -> Result<(), String> {
    heatmap::write_colorbars(&out.join("colorbar_difference.png"), &out.join("colorbar_pvalues.png"))?;
    let json = serde_json::to_string_pretty(&summary_json(results)).expect("json");
    std::fs::write(out.join("summary.json"), json).map_err(|e| e.to_string())?;
    std::fs::write(out.join("report.html"), html(results)).map_err(|e| e.to_string())
}
