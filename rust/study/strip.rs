//! Strip pictures like the paper's figures: the models left to right, each labelled, all
//! tone-mapped the same way (linear → sRGB, clipped) so brightness differences are real;
//! and the matching strip of relative-difference heatmaps against Lambert.

use super::font;
use matte_render::film::Image;
use matte_render::image_io::encode_srgb8;
use std::path::Path;

const GAP: u32 = 4;
const SCALE: u32 = 2;
const LABEL_H: u32 = 7 * SCALE + 8;

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

/// Writes the tiles side by side with their labels above, on white.
pub fn write_strip(path: &Path, tiles: &[StripTile]) -> Result<(), String> {
    let h = tiles.iter().map(|t| t.height).max().unwrap_or(1) + LABEL_H;
    let w = tiles.iter().map(|t| t.width).sum::<u32>() + GAP * (tiles.len() as u32 + 1);
    let mut buf = vec![255u8; (w * h * 3) as usize];
    let mut x0 = GAP;
    for t in tiles {
        // Half size when the label would not fit above a narrow tile.
        let scale = if font::text_width(&t.label, SCALE) <= t.width { SCALE } else { 1 };
        let tw = font::text_width(&t.label, scale);
        let lx = x0 + t.width.saturating_sub(tw) / 2;
        font::draw_text(&mut buf, w, h, lx, 4, &t.label, scale, [20, 20, 20]);
        for y in 0..t.height {
            let src = (y * t.width * 3) as usize;
            let dst = (((y + LABEL_H) * w + x0) * 3) as usize;
            buf[dst..dst + (t.width * 3) as usize].copy_from_slice(&t.rgb[src..src + (t.width * 3) as usize]);
        }
        x0 += t.width + GAP;
    }
    image::RgbImage::from_raw(w, h, buf).ok_or("strip size")?.save(path).map_err(|e| format!("{}: {e}", path.display()))
}
