//! `matte validate`'s statistics without rendering: the region → pixel rounding (one
//! implementation, `rust/matte/src/validate/crop.rs`), the multi-scale tests and the power calibration
//! (`docs/validation.md`).

use matte::validate::crop::{PixelBox, pixel_box};

/// The film widths of the rounding check (64..512): powers of two and widths where k·w/1000
/// is often a whole number, the cases binary fractions round the wrong way (0.3 · 100 =
/// 30.000000000000004 in f64).
const WIDTHS: [u32; 9] = [64, 100, 128, 200, 250, 256, 300, 400, 512];

/// The oracle: region edges k/1000 in exact integer arithmetic (first pixel ⌊k·w/1000⌋, one
/// past the last ⌈k·w/1000⌉), at least one pixel, inside the film.
fn exact_box(w: u32, h: u32, k: [u32; 4]) -> PixelBox {
    let floor = |k: u32, n: u32| k * n / 1000;
    let ceil = |k: u32, n: u32| (k * n).div_ceil(1000);
    let x0 = floor(k[0], w).min(w - 1);
    let y0 = floor(k[1], h).min(h - 1);
    PixelBox { x0, y0, x1: ceil(k[2], w).clamp(x0 + 1, w), y1: ceil(k[3], h).clamp(y0 + 1, h) }
}

#[test]
fn crop_box_rounds_decimal_fractions_exactly_at_nine_widths() {
    // Fractions as a regions.json holds them: decimal text parsed to f64 (0.35 is not exact
    // in binary). 9 widths × 999 fractions, as the start and as the end of a region.
    let mut cases = 0;
    for &w in &WIDTHS {
        let h = w / 2 + 3;
        for k in 1..1000u32 {
            let f: f64 = format!("0.{k:03}").parse().unwrap();
            // The region [0, 0, f, f] (end edge) and [f, f, 1, 1] (start edge).
            let got_end = pixel_box(w, h, [0.0, 0.0, f, f]);
            let got_start = pixel_box(w, h, [f, f, 1.0, 1.0]);
            assert_eq!(got_end, exact_box(w, h, [0, 0, k, k]), "w {w}, end {f}");
            assert_eq!(got_start, exact_box(w, h, [k, k, 1000, 1000]), "w {w}, start {f}");
            for b in [got_end, got_start] {
                // Mitsuba's Film::set_crop_window accepts it: offset + size ≤ size, size ≥ 1.
                assert!(b.x0 + b.width() <= w && b.y0 + b.height() <= h && b.area() >= 1);
            }
            cases += 2;
        }
    }
    assert_eq!(cases, 9 * 999 * 2);
}

#[test]
fn crop_box_of_an_empty_or_edge_region_is_one_pixel_inside() {
    assert_eq!(pixel_box(8, 8, [1.0, 1.0, 1.0, 1.0]), PixelBox { x0: 7, y0: 7, x1: 8, y1: 8 });
    assert_eq!(pixel_box(8, 8, [0.5, 0.5, 0.5, 0.5]), PixelBox { x0: 4, y0: 4, x1: 5, y1: 5 });
    assert_eq!(pixel_box(8, 8, [0.0, 0.0, 1.0, 1.0]), PixelBox { x0: 0, y0: 0, x1: 8, y1: 8 });
}

// ---- Tests across scales ---------------------------------------------------------------------

use glam::Vec3;
use matte::validate::power;
use matte::validate::scales::{BlockMoments, MultiScale, Scale, blocks, scales_for};
use matte_render::film::Image;

/// xorshift64* and Box–Muller: reproducible Gaussian noise without a dependency.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

/// K pass images of a constant `level` plus noise of standard deviation `sigma`, smoothed by a
/// 3 × 3 box (neighbouring pixels correlated, as a reconstruction filter makes them).
fn passes(rng: &mut Rng, w: u32, h: u32, k: usize, level: f32, sigma: f64, smooth: bool) -> Vec<Image> {
    (0..k)
        .map(|_| {
            let noise: Vec<f64> = (0..w * h * 3).map(|_| rng.normal() * sigma).collect();
            let mut img = Image::new(w, h);
            for y in 0..h as i64 {
                for x in 0..w as i64 {
                    let mut v = [0.0f64; 3];
                    let mut n = 0.0f64;
                    let r = if smooth { 1 } else { 0 };
                    for dy in -r..=r {
                        for dx in -r..=r {
                            let (xx, yy) = (x + dx, y + dy);
                            if xx >= 0 && yy >= 0 && xx < w as i64 && yy < h as i64 {
                                let i = ((yy * w as i64 + xx) * 3) as usize;
                                (0..3).for_each(|c| v[c] += noise[i + c]);
                                n += 1.0;
                            }
                        }
                    }
                    // Smoothing divides by √n so that a pixel keeps standard deviation sigma.
                    let s = if smooth { n.sqrt() } else { 1.0 };
                    img.set(
                        x as u32,
                        y as u32,
                        Vec3::splat(level) + Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32) / s as f32,
                    );
                }
            }
            img
        })
        .collect()
}

#[test]
fn every_block_grid_covers_each_pixel_once() {
    for (w, h) in [(40u32, 24u32), (256, 256), (17, 9)] {
        for s in scales_for(w, h) {
            let mut count = vec![0u32; (w * h) as usize];
            for b in blocks(s, w, h) {
                assert!(b.x0 < b.x1 && b.x1 <= w && b.y0 < b.y1 && b.y1 <= h, "{s:?} {b:?}");
                for y in b.y0..b.y1 {
                    for x in b.x0..b.x1 {
                        count[(y * w + x) as usize] += 1;
                    }
                }
            }
            let grids = if matches!(s, Scale::Block(_)) { 4 } else { 1 };
            assert!(count.iter().all(|&c| c == grids), "{w}x{h} {s:?}");
        }
    }
    assert_eq!(scales_for(32, 32), vec![Scale::Pixel, Scale::Block(4), Scale::Block(16), Scale::Image]);
}

#[test]
fn block_moments_match_a_direct_computation() {
    let mut rng = Rng(7);
    let imgs = passes(&mut rng, 10, 7, 5, 1.0, 0.3, false);
    let boxes = blocks(Scale::Block(4), 10, 7);
    let m = BlockMoments::from_images(&imgs, &boxes);
    for (i, b) in boxes.iter().enumerate() {
        // Plain loops: per pass the block's mean, then the mean and variance over passes.
        let vals: Vec<f64> = imgs
            .iter()
            .map(|img| {
                let mut s = 0.0;
                for y in b.y0..b.y1 {
                    for x in b.x0..b.x1 {
                        s += img.get(x, y).y as f64;
                    }
                }
                s / b.area() as f64
            })
            .collect();
        let mean = vals.iter().sum::<f64>() / 5.0;
        let var = vals.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 4.0 / 5.0;
        assert!((m.mean[i].y - mean).abs() < 1e-9 && (m.var_of_mean[i].y - var).abs() < 1e-9, "block {b:?}");
    }
}

#[test]
fn identical_inputs_are_rejected_at_most_at_the_family_level() {
    // 300 pairs of identically distributed, filter-correlated noise images (32², K = 16):
    // the multi-scale family at α = 0.05 must reject at most ~5 % (binomial: ≤ 26 of 300 with
    // probability > 0.99 at a true 5 %).
    let mut rng = Rng(11);
    let ms = MultiScale::new(32, 32, 0.05);
    let mut rejected = 0;
    for _ in 0..300 {
        let a = passes(&mut rng, 32, 32, 16, 1.0, 0.2, true);
        let b = passes(&mut rng, 32, 32, 16, 1.0, 0.2, true);
        rejected += ms.rejects(&a, &b) as usize;
    }
    assert!(rejected <= 26, "{rejected} of 300 rejected at α = 0.05");
}

#[test]
fn a_change_at_each_scale_is_rejected_there_with_its_place() {
    let mut rng = Rng(3);
    let ms = MultiScale::new(64, 64, 0.01);
    let a = passes(&mut rng, 64, 64, 16, 1.0, 0.1, true);
    let b = passes(&mut rng, 64, 64, 16, 1.0, 0.1, true);
    // One pixel +50 %: the pixel scale names it.
    let mut one = a.clone();
    one.iter_mut().for_each(|i| i.set(20, 30, i.get(20, 30) * 1.5));
    let r = ms.test(&one, &b);
    let px = r.iter().find(|s| s.scale == Scale::Pixel).unwrap();
    assert!(px.worst.iter().any(|q| q.place.x0 == 20 && q.place.y0 == 30), "{:?}", px.worst);
    // A 16×16 patch +5 %: below a pixel's noise (10 % per pass, t ≈ 1.4), seen by the blocks.
    let patch = power::inject(&a, 1.05, Some(PixelBox { x0: 24, y0: 8, x1: 40, y1: 24 }));
    let r = ms.test(&patch, &b);
    assert_eq!(r.iter().find(|s| s.scale == Scale::Pixel).unwrap().rejected, 0);
    let block = r.iter().find(|s| s.scale == Scale::Block(16)).unwrap();
    assert!(block.rejected > 0, "{r:?}");
    let q = &block.worst[0];
    assert!(q.place.x0 >= 16 && q.place.x1 <= 48 && q.place.y0 < 24 && q.place.y1 > 8, "{q:?}");
}

#[test]
fn measured_power_matches_the_normal_approximation_for_a_uniform_change() {
    // Independent pixels (no smoothing), 16², level 1, σ = 0.5 per pixel, K = 16 per side:
    // the image mean per pass has σ/16, the difference of the two means sd σ/16·√(2/16).
    // The whole-image test alone reaches 80 % power at δ ≈ (z_{α'/2} + z_{0.8})·sd with
    // α' = Šidák(α/S over 3 channels), S = 3 scales; t instead of z (df 30) makes it ~5 %
    // larger, and the other scales add a little power. The measured δ must fall within
    // a factor 1.6 of that (the δ grid steps are ≤ 1.5×).
    let mut rng = Rng(5);
    let (w, k, sigma) = (16u32, 16usize, 0.5);
    let reps = 40;
    let a: Vec<_> = (0..reps).map(|_| passes(&mut rng, w, w, k, 1.0, sigma, false)).collect();
    let b: Vec<_> = (0..reps).map(|_| passes(&mut rng, w, w, k, 1.0, sigma, false)).collect();
    let cal = power::calibrate(&a, &b, 0.01, &|_| {}).unwrap();
    let alpha_test = 1.0 - (1.0f64 - 0.01 / 3.0).powf(1.0 / 3.0);
    use statrs::distribution::{ContinuousCDF, Normal};
    let n = Normal::new(0.0, 1.0).unwrap();
    let sd = sigma / w as f64 * (2.0 / k as f64).sqrt();
    let predicted = (n.inverse_cdf(1.0 - alpha_test / 2.0) + n.inverse_cdf(0.8)) * sd;
    let got = cal.uniform.detected.expect("detected");
    assert!(got / predicted < 1.6 && predicted / got < 1.6, "measured {got}, predicted {predicted}");
    assert!(cal.identical_matte.rejected <= 2 && cal.identical_reference.rejected <= 2);
}

#[test]
fn predicted_power_is_a_lower_bound_close_to_injection() {
    // Correlated noise (3 × 3 smoothing, as a filter makes it), 32², K = 16 per side, 40
    // replicate pairs: injection measures the smallest uniform and 16² patch change detected
    // with 80 % power; the prediction from replicate 0 alone must not claim more power than
    // that (it is a lower bound on power, so its δ is at least the measured one, allowing one
    // step of the δ grid, ≤ 1.5×, for the measurement's own noise) and must stay within 2.5×
    // of it (useful, not vacuous).
    let mut rng = Rng(11);
    let (w, k, sigma) = (32u32, 16usize, 0.5);
    let reps = 40;
    let a: Vec<_> = (0..reps).map(|_| passes(&mut rng, w, w, k, 1.0, sigma, true)).collect();
    let b: Vec<_> = (0..reps).map(|_| passes(&mut rng, w, w, k, 1.0, sigma, true)).collect();
    let cal = power::calibrate(&a, &b, 0.01, &|_| {}).unwrap();
    let predicted = matte::validate::predicted_power::predict(&a[0], &b[0], 0.01).unwrap();
    assert_eq!(predicted.patch_place, cal.patch_place);
    for (what, measured, predicted) in [
        ("uniform", cal.uniform.detected.expect("uniform detected"), predicted.uniform.expect("uniform predicted")),
        ("patch", cal.patch.detected.expect("patch detected"), predicted.patch.expect("patch predicted")),
    ] {
        println!("{what}: measured {measured}, predicted {predicted}");
        assert!(predicted >= measured / 1.5, "{what}: predicted {predicted} claims more than measured {measured}");
        assert!(predicted <= measured * 2.5, "{what}: predicted {predicted} is far above measured {measured}");
    }
}

#[test]
fn validation_report_escapes_text_and_states_the_verdict() {
    use matte::validate::summary::Provenance;
    let provenance = Provenance {
        matte: "0.1.0".into(),
        mitsuba: None,
        references: vec!["matte".into()],
        python: None,
        scenes: "<script>alert('x')</script> & co".into(),
    };
    let html = matte::validate::validation_report::html(&[], &provenance).unwrap();
    assert!(html.starts_with("<!doctype html>") && html.trim_end().ends_with("</html>"));
    assert!(html.contains("&#60;script&#62;alert(&#39;x&#39;)&#60;/script&#62; &#38; co"), "{html}");
    assert!(!html.contains("<script>"));
    assert!(html.contains("<tr><th>Mitsuba</th><td>not run</td></tr>"));
    assert!(html.contains(r#"Overall: <span class="pass">PASS</span> — 0 scene(s)"#), "{html}");
    assert!(html.contains(r#"<table class="summary">"#));
}
