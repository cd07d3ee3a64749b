//! Strip pictures like the paper's figures: the models left to right, each labelled, all
//! tone-mapped the same way (linear → sRGB, clipped) so brightness differences are real;
//! and the matching strip of relative-difference heatmaps against Lambert.

use super::font;
use image::{Rgb, RgbImage};
use matte_render::film::Image;
use matte_render::image_io::encode_srgb8;
use std::path::Path;

const GAP: u32 = 4;
/// The labels' size in pixels per em where the tiles are wide enough (256-pixel tiles are).
pub const LABEL_PX: f32 = 16.0;
/// The smallest size labels shrink to before they are shortened.
pub const MIN_LABEL_PX: f32 = 9.0;

/// One labelled tile: RGB8 pixels of a fixed size.
pub struct StripTile {
    pub label: String,
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
}

impl StripTile {
    pub fn from_image(label: &str, img: &Image) -> StripTile {
        let rgb = img.pixels.iter().flat_map(|p| [encode_srgb8(p.x), encode_srgb8(p.y), encode_srgb8(p.z)]).collect();
        StripTile { label: label.to_string(), width: img.width, height: img.height, rgb }
    }

    /// A heatmap of signed values in [−range, range] (RdBu, red = brighter than Lambert);
    /// NaN = grey.
    pub fn from_difference(label: &str, width: u32, height: u32, rel: &[f32], range: f32) -> StripTile {
        let rgb = rel
            .iter()
            .flat_map(|&x| {
                if x.is_finite() {
                    colorous::RED_BLUE.eval_continuous((0.5 - 0.5 * x / range).clamp(0.0, 1.0) as f64).as_array()
                } else {
                    [128, 128, 128]
                }
            })
            .collect();
        StripTile { label: label.to_string(), width, height, rgb }
    }
}

/// Writes the tiles side by side with their labels above, on white. Every label has one size,
/// the largest up to [`LABEL_PX`] at which each fits its tile (at least [`MIN_LABEL_PX`]; a
/// label still too wide is shortened with "…").
pub fn write_strip(path: &Path, tiles: &[StripTile]) -> Result<(), String> {
    let fits = |t: &StripTile| LABEL_PX * t.width.saturating_sub(2) as f32 / font::width(&t.label, LABEL_PX);
    let px = tiles.iter().map(fits).fold(LABEL_PX, f32::min).max(MIN_LABEL_PX);
    let (ascent, descent) = font::extent(px);
    let label_h = (ascent - descent).ceil() as u32 + 2 * GAP;
    let h = tiles.iter().map(|t| t.height).max().unwrap_or(1) + label_h;
    let w = tiles.iter().map(|t| t.width).sum::<u32>() + GAP * (tiles.len() as u32 + 1);
    let mut strip = RgbImage::from_pixel(w, h, Rgb([255, 255, 255]));
    let mut x0 = GAP;
    for t in tiles {
        let label = font::ellipsize(&t.label, px, t.width as f32);
        let left = x0 as f32 + ((t.width as f32 - font::width(&label, px)) / 2.0).round();
        font::draw(&mut strip, left, GAP as f32, &label, px, Rgb([20, 20, 20]));
        let tile = RgbImage::from_raw(t.width, t.height, t.rgb.clone()).ok_or("tile size")?;
        image::imageops::replace(&mut strip, &tile, x0.into(), label_h.into());
        x0 += t.width + GAP;
    }
    strip.save(path).map_err(|e| format!("{}: {e}", path.display()))
}
