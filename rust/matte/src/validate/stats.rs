//! The per-pixel decision. Each renderer renders the scene in `K` independent passes (seeds);
//! per pixel and channel we know the mean of the pass values and their sample variance, and
//! test equality of the two expectations with Welch's unequal-variance t-test (Welch 1947),
//! two-sided. The family of `3·W·H` tests is held at level α with Šidák's correction
//! (`α_pixel = 1 − (1−α)^(1/N)`), as Mitsuba's own render tests do
//! (`docs/validation.md#multiple-testing`). A second, global test compares the image mean per
//! channel using the K per-pass image means, which is immune to the filter's correlation
//! between neighbouring pixels and has power against small uniform shifts. Both are scales
//! of the multi-scale family ([`super::scales`]), which also tests blocks of pixels.

use super::scales::{MultiScale, Rejection, Scale, ScaleResult};
use super::welch::welch;
use glam::{DVec3, Vec3};
use matte_render::film::Image;
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Running mean and sum of squared deviations (Welford) of K pass images, per pixel.
#[derive(Clone, Debug)]
pub struct Moments {
    pub width: u32,
    pub height: u32,
    pub passes: u32,
    mean: Vec<DVec3>,
    m2: Vec<DVec3>,
    /// Per-pass image means (for the global test).
    pub pass_means: Vec<DVec3>,
}

impl Moments {
    pub fn new(width: u32, height: u32) -> Self {
        let n = (width * height) as usize;
        Moments {
            width,
            height,
            passes: 0,
            mean: vec![DVec3::ZERO; n],
            m2: vec![DVec3::ZERO; n],
            pass_means: Vec::new(),
        }
    }

    /// Adds one pass. Panics never: a size mismatch is an error.
    pub fn add(&mut self, img: &Image) -> Result<(), String> {
        if img.width != self.width || img.height != self.height {
            return Err(format!("pass image is {}x{}, expected {}x{}", img.width, img.height, self.width, self.height));
        }
        self.passes += 1;
        let k = self.passes as f64;
        let mut sum = DVec3::ZERO;
        for (i, p) in img.pixels.iter().enumerate() {
            let x = p.as_dvec3();
            sum += x;
            let d = x - self.mean[i];
            self.mean[i] += d / k;
            self.m2[i] += d * (x - self.mean[i]);
        }
        self.pass_means.push(sum / img.pixels.len().max(1) as f64);
        Ok(())
    }

    /// Builds moments from per-pixel means and sample variances (e.g. from the Mitsuba driver).
    pub fn from_mean_var(mean: &Image, var: &Image, passes: u32, pass_means: Vec<DVec3>) -> Result<Self, String> {
        if mean.width != var.width || mean.height != var.height || passes < 2 {
            return Err("mean/variance images differ in size, or fewer than 2 passes".into());
        }
        let m2 = var.pixels.iter().map(|v| v.as_dvec3() * (passes as f64 - 1.0)).collect();
        Ok(Moments {
            width: mean.width,
            height: mean.height,
            passes,
            mean: mean.pixels.iter().map(|m| m.as_dvec3()).collect(),
            m2,
            pass_means,
        })
    }

    /// Estimate of the expected image (mean over passes).
    pub fn mean_image(&self) -> Image {
        Image { width: self.width, height: self.height, pixels: self.mean.iter().map(|m| m.as_vec3()).collect() }
    }

    /// Variance of the per-pixel mean estimate (sample variance / K).
    #[inline]
    pub fn var_of_mean(&self, i: usize) -> DVec3 {
        let k = self.passes as f64;
        self.m2[i] / ((k - 1.0) * k)
    }

    #[inline]
    pub fn mean(&self, i: usize) -> DVec3 {
        self.mean[i]
    }
}

/// Result of comparing two renderers.
#[derive(Clone, Debug)]
pub struct ImageComparison {
    pub width: u32,
    pub height: u32,
    /// Welch t statistic per pixel and channel (a − b).
    pub t: Vec<Vec3>,
    /// Two-sided p-value per pixel and channel.
    pub p: Vec<Vec3>,
    /// Relative difference (a − b) / max(|b|, floor) per pixel, channel-averaged.
    pub rel_diff: Vec<f32>,
    /// Šidák-corrected per-test level.
    pub alpha_pixel: f64,
    pub alpha: f64,
    /// Pixels with at least one channel rejected at `alpha_pixel`.
    pub rejected_pixels: usize,
    /// Fraction of channel tests with p < α (uncorrected): ≈ α when the renderers agree.
    pub uncorrected_rejection_rate: f64,
    pub global: GlobalTest,
    /// Every scale's outcome (pixels, blocks, whole image; `docs/validation.md#tests-across-scales`).
    pub scales: Vec<ScaleResult>,
}

/// The image-mean comparison per channel.
#[derive(Clone, Copy, Debug)]
pub struct GlobalTest {
    pub mean_a: DVec3,
    pub mean_b: DVec3,
    /// a − b and the half-width of its 99 % confidence interval (Welch).
    pub diff: DVec3,
    pub ci99: DVec3,
    pub p: DVec3,
    /// Rejected by the whole-image scale of the multi-scale family.
    pub rejected: bool,
}

impl ImageComparison {
    pub fn passed(&self) -> bool {
        self.scales.iter().all(|s| s.rejected == 0)
    }

    /// All kept rejections over the scales, most significant first.
    pub fn ranked_rejections(&self) -> Vec<&Rejection> {
        let mut v: Vec<&Rejection> = self.scales.iter().flat_map(|s| &s.worst).collect();
        v.sort_by(|x, y| x.p.total_cmp(&y.p));
        v
    }

    pub fn rejected_fraction(&self) -> f64 {
        self.rejected_pixels as f64 / (self.width as f64 * self.height as f64)
    }
}

/// Compares renderer `a` with renderer `b` (their pass images and moments) at family level
/// `alpha` over all scales.
pub fn compare(
    a_images: &[Image],
    a: &Moments,
    b_images: &[Image],
    b: &Moments,
    alpha: f64,
) -> Result<ImageComparison, String> {
    if a.width != b.width || a.height != b.height {
        return Err(format!("image sizes differ: {}x{} vs {}x{}", a.width, a.height, b.width, b.height));
    }
    if a.passes < 2 || b.passes < 2 {
        return Err("each renderer needs at least 2 passes to estimate its variance".into());
    }
    let n = (a.width * a.height) as usize;
    let scales = MultiScale::new(a.width, a.height, alpha).test(a_images, b_images);
    let alpha_pixel = scales.iter().find(|s| s.scale == Scale::Pixel).map(|s| s.alpha_test).unwrap_or(0.0);
    let mut t = Vec::with_capacity(n);
    let mut p = Vec::with_capacity(n);
    let mut rel = Vec::with_capacity(n);
    let mut uncorrected = 0usize;
    for i in 0..n {
        let (ma, mb, va, vb) = (a.mean(i), b.mean(i), a.var_of_mean(i), b.var_of_mean(i));
        let mut tv = Vec3::ZERO;
        let mut pv = Vec3::ZERO;
        for c in 0..3 {
            let (tc, pc) = welch(ma[c], va[c], a.passes, mb[c], vb[c], b.passes);
            tv[c] = tc as f32;
            pv[c] = pc as f32;
            uncorrected += (pc < alpha) as usize;
        }
        t.push(tv);
        p.push(pv);
        let floor = 1e-3;
        rel.push((((ma - mb) / mb.abs().max(DVec3::splat(floor))).element_sum() / 3.0) as f32);
    }
    let mut global = global_test(&a.pass_means, &b.pass_means);
    global.rejected = scales.iter().any(|s| s.scale == Scale::Image && s.rejected > 0);
    let rejected = scales.iter().find(|s| s.scale == Scale::Pixel).map(|s| s.rejected).unwrap_or(0);
    Ok(ImageComparison {
        width: a.width,
        height: a.height,
        t,
        p,
        rel_diff: rel,
        alpha_pixel,
        alpha,
        rejected_pixels: rejected,
        uncorrected_rejection_rate: uncorrected as f64 / (3 * n) as f64,
        global,
        scales,
    })
}

fn mean_var(xs: &[DVec3]) -> (DVec3, DVec3) {
    let k = xs.len() as f64;
    let m = xs.iter().copied().sum::<DVec3>() / k;
    let v = xs.iter().map(|x| (*x - m) * (*x - m)).sum::<DVec3>() / (k - 1.0);
    (m, v)
}

fn global_test(a: &[DVec3], b: &[DVec3]) -> GlobalTest {
    let (ma, va) = mean_var(a);
    let (mb, vb) = mean_var(b);
    let (ka, kb) = (a.len() as u32, b.len() as u32);
    let mut p = DVec3::ZERO;
    let mut ci = DVec3::ZERO;
    for c in 0..3 {
        let (sa, sb) = (va[c] / ka as f64, vb[c] / kb as f64);
        let (_, pc) = welch(ma[c], sa, ka, mb[c], sb, kb);
        p[c] = pc;
        let se2 = sa + sb;
        let df = (se2 * se2 / (sa * sa / (ka as f64 - 1.0) + sb * sb / (kb as f64 - 1.0)).max(1e-300)).clamp(1.0, 1e6);
        let q = StudentsT::new(0.0, 1.0, df).expect("t").inverse_cdf(0.995);
        ci[c] = q * se2.sqrt();
    }
    GlobalTest { mean_a: ma, mean_b: mb, diff: ma - mb, ci99: ci, p, rejected: false }
}
