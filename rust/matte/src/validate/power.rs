//! What the budget can see (`docs/validation.md#power`): the smallest relative change that
//! the multi-scale test detects with 80 % power, measured by injection. `matte validate
//! --power` renders R independent replicates of both sides (R × K passes each, replicate 0
//! being the run the verdict comes from); a known factor `1 ± δ` is injected into the
//! matte side's saved pass images (the whole image, or one 16 × 16 patch), each replicate
//! pair is tested, and the power at δ is the fraction of pairs rejected. The sign alternates
//! over replicates, so a small real difference between the renderers neither helps nor hides.
//! No re-rendering: the change is applied to the images, which is what a change in
//! radiance of that size does to them.
//!
//! The same replicates give the test's size on identical inputs: replicate pairs of one
//! renderer (matte against matte, reference against reference, other seeds) should be rejected
//! in at most α of the pairs.

use super::crop::PixelBox;
use super::scales::{BlockMoments, MultiScale};
use matte_render::film::Image;

/// Relative changes tried, smallest first.
pub const DELTAS: [f64; 19] = [
    0.0005, 0.00075, 0.001, 0.0015, 0.002, 0.003, 0.004, 0.005, 0.0075, 0.01, 0.015, 0.02, 0.03, 0.05, 0.075, 0.1,
    0.15, 0.2, 0.3,
];

/// The power the report states.
pub const TARGET_POWER: f64 = 0.8;

/// Side of the injected patch (pixels).
pub const PATCH: u32 = 16;

/// Rejections out of pairs.
#[derive(Clone, Debug, Default)]
pub struct Rate {
    pub rejected: usize,
    pub pairs: usize,
    /// Pairs rejected by each scale (a pair may count at several scales).
    pub by_scale: Vec<(String, usize)>,
}

impl Rate {
    pub fn fraction(&self) -> f64 {
        self.rejected as f64 / self.pairs.max(1) as f64
    }
}

/// One injection kind's power curve and the smallest δ with 80 % power.
#[derive(Clone, Debug, Default)]
pub struct PowerCurve {
    /// (δ, power) in increasing δ, up to the first δ reaching the target.
    pub curve: Vec<(f64, f64)>,
    /// Smallest δ of [`DELTAS`] with power ≥ [`TARGET_POWER`]; `None` when none reaches it.
    pub detected: Option<f64>,
}

#[derive(Clone, Debug)]
pub struct Calibration {
    pub replicates: usize,
    /// matte vs reference, replicate by replicate, without injection.
    pub unchanged: Rate,
    /// matte vs matte and reference vs reference (disjoint replicate pairs).
    pub identical_matte: Rate,
    pub identical_reference: Rate,
    pub uniform: PowerCurve,
    pub patch: PowerCurve,
    /// Where the patch sits.
    pub patch_place: PixelBox,
}

fn luminance(c: glam::Vec3) -> f64 {
    (0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z) as f64
}

/// The patch: among the 16 × 16 tiles of the reference's mean image that are not black, the
/// one of median luminance (a typical lit surface), then moved by half a tile so that it
/// straddles the block grids' lines rather than matching a block.
pub fn patch_place(mean: &Image) -> PixelBox {
    let (w, h) = (mean.width, mean.height);
    let (pw, ph) = (PATCH.min(w), PATCH.min(h));
    let mut tiles: Vec<(f64, u32, u32)> = Vec::new();
    for ty in 0..(h / ph).max(1) {
        for tx in 0..(w / pw).max(1) {
            let (x0, y0) = (tx * pw, ty * ph);
            let mut sum = 0.0;
            for y in y0..y0 + ph {
                for x in x0..x0 + pw {
                    sum += luminance(mean.get(x, y));
                }
            }
            tiles.push((sum, x0, y0));
        }
    }
    let top = tiles.iter().map(|t| t.0).fold(0.0, f64::max);
    let mut lit: Vec<_> = tiles.iter().filter(|t| t.0 > 1e-3 * top).copied().collect();
    lit.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (_, x0, y0) = lit.get(lit.len() / 2).copied().unwrap_or((0.0, 0, 0));
    let shift = |x: u32, p: u32, n: u32| if x + p + p / 2 <= n { x + p / 2 } else { x.saturating_sub(p / 2) };
    let (x0, y0) = (shift(x0, pw, w), shift(y0, ph, h));
    PixelBox { x0, y0, x1: x0 + pw, y1: y0 + ph }
}

/// `images` with every pixel (or only those in `place`) multiplied by `factor`.
pub fn inject(images: &[Image], factor: f32, place: Option<PixelBox>) -> Vec<Image> {
    images
        .iter()
        .map(|img| {
            let mut out = img.clone();
            match place {
                None => out.pixels.iter_mut().for_each(|p| *p *= factor),
                Some(b) => {
                    for y in b.y0..b.y1 {
                        for x in b.x0..b.x1 {
                            out.set(x, y, img.get(x, y) * factor);
                        }
                    }
                }
            }
            out
        })
        .collect()
}

fn any_rejects(ms: &MultiScale, a: &[BlockMoments], b: &[BlockMoments]) -> bool {
    ms.test_moments(a, b).iter().any(|r| r.rejected > 0)
}

fn rate<'a>(ms: &MultiScale, pairs: impl Iterator<Item = (&'a [BlockMoments], &'a [BlockMoments])>) -> Rate {
    let mut out = Rate { by_scale: ms.scales.iter().map(|(s, _)| (s.key(), 0)).collect(), ..Default::default() };
    for (a, b) in pairs {
        let r = ms.test_moments(a, b);
        out.pairs += 1;
        out.rejected += r.iter().any(|s| s.rejected > 0) as usize;
        for (count, s) in out.by_scale.iter_mut().zip(&r) {
            count.1 += (s.rejected > 0) as usize;
        }
    }
    out
}

fn identical_rate(ms: &MultiScale, moments: &[Vec<BlockMoments>]) -> Rate {
    rate(ms, moments.chunks_exact(2).map(|p| (p[0].as_slice(), p[1].as_slice())))
}

fn power_curve(
    ms: &MultiScale,
    a: &[Vec<Image>],
    b_moments: &[Vec<BlockMoments>],
    place: Option<PixelBox>,
    progress: &dyn Fn(&str),
) -> PowerCurve {
    let mut out = PowerCurve::default();
    for &d in &DELTAS {
        let rejected = a
            .iter()
            .zip(b_moments)
            .enumerate()
            .filter(|(r, (a, b))| {
                let sign = if r % 2 == 0 { 1.0 } else { -1.0 };
                let injected = inject(a, (1.0 + sign * d) as f32, place);
                any_rejects(ms, &ms.moments(&injected), b)
            })
            .count();
        let power = rejected as f64 / a.len().max(1) as f64;
        out.curve.push((d, power));
        progress(&format!("δ = {:.2}%: power {:.2}", d * 100.0, power));
        if power >= TARGET_POWER {
            out.detected = Some(d);
            break;
        }
    }
    out
}

/// Calibrates the test on R replicates of each side (`a[r]`, `b[r]`: K pass images each).
pub fn calibrate(
    a: &[Vec<Image>],
    b: &[Vec<Image>],
    alpha: f64,
    progress: &dyn Fn(&str),
) -> Result<Calibration, String> {
    let first = a.first().and_then(|r| r.first()).ok_or("power calibration: no replicates")?;
    if a.len() != b.len() || a.len() < 2 {
        return Err("power calibration: needs at least 2 replicates of each side".into());
    }
    let ms = MultiScale::new(first.width, first.height, alpha);
    let am: Vec<_> = a.iter().map(|r| ms.moments(r)).collect();
    let bm: Vec<_> = b.iter().map(|r| ms.moments(r)).collect();
    let unchanged = rate(&ms, am.iter().zip(&bm).map(|(x, y)| (x.as_slice(), y.as_slice())));
    let identical_matte = identical_rate(&ms, &am);
    let identical_reference = identical_rate(&ms, &bm);
    // The reference's mean image over all replicates places the patch.
    let mut mean = Image::new(first.width, first.height);
    let n = b.iter().map(|r| r.len()).sum::<usize>() as f32;
    for img in b.iter().flatten() {
        mean.pixels.iter_mut().zip(&img.pixels).for_each(|(m, p)| *m += *p / n);
    }
    let place = patch_place(&mean);
    progress("uniform change");
    let uniform = power_curve(&ms, a, &bm, None, progress);
    progress("16×16 patch");
    let patch = power_curve(&ms, a, &bm, Some(place), progress);
    Ok(Calibration {
        replicates: a.len(),
        unchanged,
        identical_matte,
        identical_reference,
        uniform,
        patch,
        patch_place: place,
    })
}
