//! Tests at several scales (`docs/validation.md#tests-across-scales`): a difference may be one
//! pixel wide (a rim, a shifted edge), a few pixels (a filter's footprint), an object or a
//! shadow (tens of pixels), or the whole image. Each scale averages the pass images over
//! blocks of `s × s` pixels, per pass, and tests every block and channel with Welch's test on
//! the K per-pass block means of each side ([`super::welch::welch`]). Block means of
//! independent passes are independent whatever the reconstruction filter does inside a pass,
//! so the test is valid at every scale.
//!
//! Scales: pixels (s = 1), blocks of 4², 16² and 64² pixels on four grids each (offsets 0 and
//! s/2 in x and y, so a patch is never split in four by the grid), and the whole image. Within
//! a scale the tests are held at the scale's level with Šidák's correction over all its blocks
//! and channels; over the scales with Bonferroni (each scale gets α / number of scales). The
//! family-wise error over all scales is then at most α (Šidák is exact for independent tests
//! and conservative for positively correlated ones, Bonferroni holds for any dependence).

use super::crop::PixelBox;
use super::welch::{sidak, welch};
use glam::DVec3;
use matte_render::film::Image;
use statrs::distribution::{ContinuousCDF, Normal};

/// One scale of the family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    Pixel,
    /// Square blocks of this side (pixels) on four half-offset grids.
    Block(u32),
    Image,
}

impl Scale {
    pub fn label(&self) -> String {
        match self {
            Scale::Pixel => "pixel".into(),
            Scale::Block(s) => format!("{s}×{s} blocks"),
            Scale::Image => "whole image".into(),
        }
    }

    pub fn key(&self) -> String {
        match self {
            Scale::Pixel => "pixel".into(),
            Scale::Block(s) => format!("block{s}"),
            Scale::Image => "image".into(),
        }
    }
}

/// Block sides of the block scales.
pub const BLOCK_SIDES: [u32; 3] = [4, 16, 64];

/// The scales for a `width × height` image: pixels, each block side smaller than the image
/// (a block as large as the image is the whole-image test), the whole image.
pub fn scales_for(width: u32, height: u32) -> Vec<Scale> {
    let mut v = vec![Scale::Pixel];
    v.extend(BLOCK_SIDES.iter().filter(|&&s| s < width.max(height)).map(|&s| Scale::Block(s)));
    v.push(Scale::Image);
    v
}

/// The blocks of a scale: pixel boxes, clipped to the image (edge blocks are smaller).
pub fn blocks(scale: Scale, width: u32, height: u32) -> Vec<PixelBox> {
    match scale {
        Scale::Pixel => {
            (0..height).flat_map(|y| (0..width).map(move |x| PixelBox { x0: x, y0: y, x1: x + 1, y1: y + 1 })).collect()
        }
        Scale::Image => vec![PixelBox { x0: 0, y0: 0, x1: width, y1: height }],
        Scale::Block(s) => {
            let mut v = Vec::new();
            for (ox, oy) in [(0, 0), (s / 2, 0), (0, s / 2), (s / 2, s / 2)] {
                // Grid lines at o, o + s, …; the first block of an offset grid starts at 0.
                let edges = |o: u32, n: u32| {
                    let mut e = vec![0];
                    let mut x = if o == 0 { s } else { o };
                    while x < n {
                        e.push(x);
                        x += s;
                    }
                    e.push(n);
                    e
                };
                let (ex, ey) = (edges(ox, width), edges(oy, height));
                for wy in ey.windows(2) {
                    for wx in ex.windows(2) {
                        v.push(PixelBox { x0: wx[0], y0: wy[0], x1: wx[1], y1: wy[1] });
                    }
                }
            }
            v
        }
    }
}

/// Per block: the mean over passes of the block means and the variance of that mean
/// (sample variance over passes / K).
#[derive(Clone, Debug)]
pub struct BlockMoments {
    pub passes: u32,
    pub mean: Vec<DVec3>,
    pub var_of_mean: Vec<DVec3>,
}

impl BlockMoments {
    /// From the pass images of one side (all of one size, at least 2).
    pub fn from_images(images: &[Image], boxes: &[PixelBox]) -> BlockMoments {
        let k = images.len();
        let w = images.first().map(|i| i.width).unwrap_or(0) as usize;
        let n = boxes.len();
        let mut mean = vec![DVec3::ZERO; n];
        let mut m2 = vec![DVec3::ZERO; n];
        // A summed-area table per pass makes every block O(1) whatever its size.
        let mut sat: Vec<DVec3> = Vec::new();
        for (j, img) in images.iter().enumerate() {
            summed_area(img, &mut sat);
            let kj = (j + 1) as f64;
            for (b, bx) in boxes.iter().enumerate() {
                let x = box_sum(&sat, w + 1, bx) / bx.area() as f64;
                let d = x - mean[b];
                mean[b] += d / kj;
                m2[b] += d * (x - mean[b]);
            }
        }
        let kf = k as f64;
        let var_of_mean = m2.iter().map(|m| *m / ((kf - 1.0).max(1.0) * kf)).collect();
        BlockMoments { passes: k as u32, mean, var_of_mean }
    }
}

/// Summed-area table with a zero row and column in front: `(w + 1) × (h + 1)`.
fn summed_area(img: &Image, sat: &mut Vec<DVec3>) {
    let (w, h) = (img.width as usize, img.height as usize);
    sat.clear();
    sat.resize((w + 1) * (h + 1), DVec3::ZERO);
    for y in 0..h {
        let mut row = DVec3::ZERO;
        for x in 0..w {
            row += img.pixels[y * w + x].as_dvec3();
            sat[(y + 1) * (w + 1) + x + 1] = sat[y * (w + 1) + x + 1] + row;
        }
    }
}

fn box_sum(sat: &[DVec3], stride: usize, b: &PixelBox) -> DVec3 {
    let (x0, y0, x1, y1) = (b.x0 as usize, b.y0 as usize, b.x1 as usize, b.y1 as usize);
    sat[y1 * stride + x1] - sat[y0 * stride + x1] - sat[y1 * stride + x0] + sat[y0 * stride + x0]
}

/// A rejected block: where, how strongly, by how much.
#[derive(Clone, Debug)]
pub struct Rejection {
    pub scale: Scale,
    pub place: PixelBox,
    /// Smallest p over the channels.
    pub p: f64,
    /// Welch t per channel (a − b).
    pub t: DVec3,
    /// Channel-averaged relative difference (a − b) / max(|b|, 1e-3) of the block means.
    pub rel_diff: f64,
}

/// One scale's outcome.
#[derive(Clone, Debug)]
pub struct ScaleResult {
    pub scale: Scale,
    /// Number of blocks (tests = 3 × blocks).
    pub blocks: usize,
    /// Per-test level: Šidák over 3 × blocks at this scale's share of α.
    pub alpha_test: f64,
    /// Number of rejected blocks.
    pub rejected: usize,
    /// The most significant rejections (at most [`KEEP`]), smallest p first.
    pub worst: Vec<Rejection>,
    /// Smallest p at this scale (when no test came near the level: the p of the largest |t|,
    /// which is the smallest p up to the small spread of the tests' degrees of freedom).
    pub min_p: f64,
}

/// Rejections kept per scale for the report.
pub const KEEP: usize = 24;

/// Per-test level of `scale` on a `width × height` image at family level `alpha` over
/// `n_scales` scales (Bonferroni over scales, Šidák within).
pub fn alpha_test(alpha: f64, n_scales: usize, n_blocks: usize) -> f64 {
    sidak(alpha / n_scales.max(1) as f64, 3 * n_blocks)
}

/// Tests every block and channel of `scale`. p is computed only for tests whose |t| reaches
/// the normal quantile of the level (no t quantile is smaller), which keeps the power
/// calibration's thousands of repeats fast; the pixel heatmap computes every p itself.
pub fn test_scale(
    scale: Scale,
    boxes: &[PixelBox],
    a: &BlockMoments,
    b: &BlockMoments,
    alpha_test: f64,
) -> ScaleResult {
    // |t| below the normal quantile can never reject: t quantiles exceed it at any df.
    let z = Normal::new(0.0, 1.0).expect("normal").inverse_cdf(1.0 - alpha_test / 2.0);
    let mut rejected = Vec::new();
    let mut count = 0;
    let mut min_p = 1.0f64;
    // The largest |t| and its test, for the smallest p when no test came near the level.
    let mut largest = (0.0f64, 0usize, 0usize);
    for (i, bx) in boxes.iter().enumerate() {
        let (ma, mb, va, vb) = (a.mean[i], b.mean[i], a.var_of_mean[i], b.var_of_mean[i]);
        let mut pmin = 1.0f64;
        let mut t = DVec3::ZERO;
        let mut any = false;
        for c in 0..3 {
            let floor = (1e-6 * ma[c].abs().max(mb[c].abs())).powi(2) + 1e-24;
            t[c] = (ma[c] - mb[c]) / (va[c] + vb[c] + floor).sqrt();
            if t[c].abs() > largest.0 {
                largest = (t[c].abs(), i, c);
            }
            if t[c].abs() >= z {
                let (_, p) = welch(ma[c], va[c], a.passes, mb[c], vb[c], b.passes);
                pmin = pmin.min(p);
                any |= p < alpha_test;
            }
        }
        min_p = min_p.min(pmin);
        if any {
            count += 1;
            let rel = ((ma - mb) / mb.abs().max(DVec3::splat(1e-3))).element_sum() / 3.0;
            rejected.push(Rejection { scale, place: *bx, p: pmin, t, rel_diff: rel });
        }
    }
    if min_p == 1.0 && largest.0 > 0.0 {
        let (_, i, c) = largest;
        min_p = welch(a.mean[i][c], a.var_of_mean[i][c], a.passes, b.mean[i][c], b.var_of_mean[i][c], b.passes).1;
    }
    rejected.sort_by(|x, y| x.p.total_cmp(&y.p));
    rejected.truncate(KEEP);
    ScaleResult { scale, blocks: boxes.len(), alpha_test, rejected: count, worst: rejected, min_p }
}

/// The pass images of both sides, with each scale's blocks prepared once.
pub struct MultiScale {
    pub width: u32,
    pub height: u32,
    pub alpha: f64,
    pub scales: Vec<(Scale, Vec<PixelBox>)>,
}

impl MultiScale {
    pub fn new(width: u32, height: u32, alpha: f64) -> MultiScale {
        let scales = scales_for(width, height).into_iter().map(|s| (s, blocks(s, width, height))).collect();
        MultiScale { width, height, alpha, scales }
    }

    /// Each scale's block moments of one side.
    pub fn moments(&self, images: &[Image]) -> Vec<BlockMoments> {
        self.scales.iter().map(|(_, boxes)| BlockMoments::from_images(images, boxes)).collect()
    }

    /// Tests one side's block moments against the other's (both from [`Self::moments`]).
    pub fn test_moments(&self, a: &[BlockMoments], b: &[BlockMoments]) -> Vec<ScaleResult> {
        let n = self.scales.len();
        self.scales
            .iter()
            .zip(a.iter().zip(b))
            .map(|((s, boxes), (ma, mb))| test_scale(*s, boxes, ma, mb, alpha_test(self.alpha, n, boxes.len())))
            .collect()
    }

    /// Tests `a` against `b` at every scale.
    pub fn test(&self, a: &[Image], b: &[Image]) -> Vec<ScaleResult> {
        self.test_moments(&self.moments(a), &self.moments(b))
    }

    /// Whether any scale rejects.
    pub fn rejects(&self, a: &[Image], b: &[Image]) -> bool {
        self.test(a, b).iter().any(|r| r.rejected > 0)
    }
}
