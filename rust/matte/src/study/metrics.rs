//! The numbers the study reports: the image-mean luminance ratio of a model to Lambert with
//! a 99 % confidence interval, and where the per-pixel difference concentrates (edges vs
//! flat regions).
//!
//! Every model is rendered with the same seeds, pass by pass, so pass k of a model and
//! pass k of Lambert share their random numbers: the per-pass ratios are paired, which
//! removes most of the common noise from the ratio's interval.

use super::ratio::Ratio;
use crate::validate::stats::Moments;
use glam::{DVec3, Vec3};
use matte_render::film::Image;
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Rec. 709 / sRGB luminance of linear RGB.
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

fn luminance_d(c: DVec3) -> f64 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// Mean and 99 % half-width (Student t) of a sample.
pub fn mean_ci99(xs: &[f64]) -> Ratio {
    let k = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / k;
    if xs.len() < 2 {
        return Ratio::new(m, f64::NAN);
    }
    let v = xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (k - 1.0);
    let q = StudentsT::new(0.0, 1.0, k - 1.0).expect("t").inverse_cdf(0.995);
    Ratio::new(m, q * (v / k).sqrt())
}

/// Ratio of image-mean luminance, model / Lambert, from paired passes, with its 99 % interval.
pub fn luminance_ratio(model: &Moments, lambert: &Moments) -> Ratio {
    paired_luminance_ratio(&model.pass_means, &lambert.pass_means)
}

/// Mean and 99 % interval of the per-pass luminance ratios of paired pass means.
pub fn paired_luminance_ratio(model: &[DVec3], lambert: &[DVec3]) -> Ratio {
    mean_ci99(&pass_ratios(model, lambert))
}

/// The per-pass luminance ratios of paired pass means, model / reference.
pub fn pass_ratios(model: &[DVec3], reference: &[DVec3]) -> Vec<f64> {
    model.iter().zip(reference).map(|(m, r)| luminance_d(*m) / luminance_d(*r).max(1e-12)).collect()
}

/// Δ = |r_global − 1| − |r_direct − 1| with its 99 % interval, from the per-pass ratios of
/// both lightings (pass k of each shares its seed). Each |· − 1| takes its sign from the mean
/// ratio, so Δ is linear in the passes: the mean of the per-pass
/// `s_g (r_global,k − 1) − s_d (r_direct,k − 1)` is Δ exactly, and its Student-t interval is
/// paired per seed. Positive: further from the reference under global illumination.
pub fn growth(global: &[f64], direct: &[f64]) -> Ratio {
    let sign = |xs: &[f64]| if xs.iter().sum::<f64>() / xs.len() as f64 >= 1.0 { 1.0 } else { -1.0 };
    let (sg, sd) = (sign(global), sign(direct));
    let d: Vec<f64> = global.iter().zip(direct).map(|(g, d)| sg * (g - 1.0) - sd * (d - 1.0)).collect();
    mean_ci99(&d)
}

/// Per-pixel relative luminance difference (model − Lambert) / Lambert; pixels darker than
/// `floor` in Lambert get NaN (no meaningful ratio).
pub fn relative_difference(model: &Image, lambert: &Image, floor: f32) -> Vec<f32> {
    model
        .pixels
        .iter()
        .zip(&lambert.pixels)
        .map(|(m, l)| {
            let (ym, yl) = (luminance(*m), luminance(*l));
            if yl > floor { (ym - yl) / yl } else { f32::NAN }
        })
        .collect()
}

/// Edge mask from an image: the pixels whose log-luminance gradient (central differences) is
/// in the top `fraction` of the image. Edges are silhouettes, creases and shadow borders.
pub fn edge_mask(img: &Image, fraction: f64) -> Vec<bool> {
    let (w, h) = (img.width as usize, img.height as usize);
    let ly: Vec<f32> = img.pixels.iter().map(|p| (luminance(*p).max(0.0) + 1e-3).ln()).collect();
    let at = |x: usize, y: usize| ly[y * w + x];
    let mut g = vec![0.0f32; w * h];
    for y in 0..h {
        for x in 0..w {
            let gx = at((x + 1).min(w - 1), y) - at(x.saturating_sub(1), y);
            let gy = at(x, (y + 1).min(h - 1)) - at(x, y.saturating_sub(1));
            g[y * w + x] = (gx * gx + gy * gy).sqrt();
        }
    }
    let mut sorted = g.clone();
    sorted.sort_by(f32::total_cmp);
    let thr = sorted[((sorted.len() as f64 * (1.0 - fraction)) as usize).min(sorted.len() - 1)];
    g.iter().map(|&v| v > thr).collect()
}

/// Colour-scale half-range of a heatmap strip: the 95th percentile of |difference| over all
/// its tiles, rounded up to 5 %, within [5 %, 100 %] (one scale per strip, so tiles compare).
pub fn heatmap_range(rels: &[Vec<f32>]) -> f32 {
    let mut all: Vec<f32> = rels.iter().flatten().map(|x| x.abs()).filter(|x| x.is_finite()).collect();
    all.sort_by(f32::total_cmp);
    let p95 = all.get((all.len() as f32 * 0.95) as usize).copied().unwrap_or(0.05);
    (p95.clamp(0.05, 1.0) * 20.0).ceil() / 20.0
}

/// Mean |relative difference| on edge pixels and on the rest (NaN pixels skipped).
pub fn edge_vs_flat(rel: &[f32], edges: &[bool]) -> (f64, f64) {
    let (mut se, mut ne, mut sf, mut nf) = (0.0, 0usize, 0.0, 0usize);
    for (r, &e) in rel.iter().zip(edges) {
        if !r.is_finite() {
            continue;
        }
        if e {
            se += r.abs() as f64;
            ne += 1;
        } else {
            sf += r.abs() as f64;
            nf += 1;
        }
    }
    (se / ne.max(1) as f64, sf / nf.max(1) as f64)
}
