//! What the budget can see, predicted from one run (`docs/validation.md#power`): no
//! replicates, so every `matte validate` (and `make main`'s report) states it. For a change
//! `1 + δ` of the matte side's radiance (everywhere, or in the 16 × 16 patch that
//! [`super::power`] injects), each block test's statistic shifts by `δ·s` standard errors,
//! with `s` = (the block mean's change per unit δ) / (the block's standard error), both from
//! this run's pass images. A single test with Welch df ν at level α′ rejects with probability
//! `P(|T_ν + δ·s| > t_{ν, 1−α′/2})`, T_ν Student's t (the shifted central t standing in for
//! the noncentral one). The family rejects whenever any test does, so the largest of these
//! probabilities is a **lower bound** on the family's power; the prediction is the smallest δ
//! where that bound reaches 80 %, a conservative (larger) figure than injection measures.
//! `tests/tools/validate_stats.rs` checks it against injection over replicates.

use super::crop::PixelBox;
use super::power::{TARGET_POWER, patch_place};
use super::scales::{BlockMoments, MultiScale, alpha_test};
use super::welch::welch_df;
use matte_render::film::Image;
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Smallest relative changes detected with at least 80 % power, by the bound above.
#[derive(Clone, Debug)]
pub struct Prediction {
    /// A change of the whole image; `None` when no test can see one (a black image).
    pub uniform: Option<f64>,
    /// A change confined to `patch_place`.
    pub patch: Option<f64>,
    pub patch_place: PixelBox,
}

/// The prediction for matte's pass images `a` against the reference's `b` (K ≥ 2 each) at
/// family level `alpha`.
pub fn predict(a: &[Image], b: &[Image], alpha: f64) -> Result<Prediction, String> {
    let first = a.first().ok_or("power prediction: no passes")?;
    if a.len() < 2 || b.len() < 2 {
        return Err("power prediction: needs at least 2 passes of each side".into());
    }
    let ms = MultiScale::new(first.width, first.height, alpha);
    let (am, bm) = (ms.moments(a), ms.moments(b));
    let mean_a = mean_image(a);
    let place = patch_place(&mean_image(b));
    let mut in_patch = Image::new(mean_a.width, mean_a.height);
    for y in place.y0..place.y1 {
        for x in place.x0..place.x1 {
            in_patch.set(x, y, mean_a.get(x, y));
        }
    }
    Ok(Prediction {
        uniform: smallest_detected(&ms, &am, &bm, &mean_a),
        patch: smallest_detected(&ms, &am, &bm, &in_patch),
        patch_place: place,
    })
}

/// The per-pixel mean of pass images.
fn mean_image(images: &[Image]) -> Image {
    let mut mean = Image::new(images[0].width, images[0].height);
    let n = images.len() as f32;
    for img in images {
        mean.pixels.iter_mut().zip(&img.pixels).for_each(|(m, p)| *m += *p / n);
    }
    mean
}

/// Smallest δ at which some test's rejection probability reaches [`TARGET_POWER`], when the
/// matte side's radiance changes by `δ × change` (an image: the mean radiance where it
/// changes, zero elsewhere).
fn smallest_detected(ms: &MultiScale, a: &[BlockMoments], b: &[BlockMoments], change: &Image) -> Option<f64> {
    let n = ms.scales.len();
    let mut best: Option<f64> = None;
    for ((_, boxes), (ma, mb)) in ms.scales.iter().zip(a.iter().zip(b)) {
        let level = alpha_test(ms.alpha, n, boxes.len());
        // Block means of the change per unit δ (one "pass": the change image itself).
        let shift = BlockMoments::from_images(std::slice::from_ref(change), boxes).mean;
        for (i, d) in shift.iter().enumerate() {
            for c in 0..3 {
                let (va, vb) = (ma.var_of_mean[i][c], mb.var_of_mean[i][c]);
                let floor = (1e-6 * ma.mean[i][c].abs().max(mb.mean[i][c].abs())).powi(2) + 1e-24;
                let se = (va + vb + floor).sqrt();
                let s = d[c].abs() / se;
                if s <= 0.0 || !s.is_finite() {
                    continue;
                }
                // Quick reject: this test cannot beat the best δ so far even with ν = ∞
                // (t quantiles only exceed the normal ones, so δ ≥ z/s).
                if best.is_some_and(|b| b * s < 1.0) {
                    continue;
                }
                let df = welch_df(va, ma.passes, vb, mb.passes, floor);
                if let Some(delta) = detected_at(s, df, level)
                    && best.is_none_or(|b| delta < b)
                {
                    best = Some(delta);
                }
            }
        }
    }
    best
}

/// Smallest δ with `P(|T_ν + δ·s| > t_{ν, 1−level/2}) ≥ TARGET_POWER` (bisection: the
/// probability grows with δ).
fn detected_at(s: f64, df: f64, level: f64) -> Option<f64> {
    let t = StudentsT::new(0.0, 1.0, df).ok()?;
    let crit = t.inverse_cdf(1.0 - level / 2.0);
    let power = |delta: f64| {
        let shift = delta * s;
        t.sf(crit - shift) + t.cdf(-crit - shift)
    };
    let (mut lo, mut hi) = (0.0, 1.0 / s);
    while power(hi) < TARGET_POWER {
        hi *= 2.0;
        if hi > 1e6 {
            return None;
        }
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if power(mid) < TARGET_POWER { lo = mid } else { hi = mid }
    }
    Some(hi)
}
