//! `matte validate`'s statistics without rendering: the region → pixel rounding (one
//! implementation, `rust/validate/crop.rs`), the multi-scale tests and the power calibration
//! (`docs/validation.md`).

use matte::validate::crop::{PixelBox, pixel_box};

/// The film widths of the rounding check (64..512).
const WIDTHS: [u32; 9] = [64, 96, 128, 160, 192, 256, 320, 384, 512];

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
