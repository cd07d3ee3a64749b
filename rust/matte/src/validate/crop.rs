//! The one conversion from an image region given as fractions of the film
//! (`<scene>.regions.json`, `[x0, y0, x1, y1]` in [0, 1]) to whole pixels
//! (`docs/validation.md#regions-and-crop-windows`). Both renderers use its result: the Rust
//! side averages these pixels, the study sets them as the film's crop window
//! (`crop_offset_x/y`, `crop_width/height`), and the Mitsuba driver only renders (it never
//! rounds a fraction itself).
//!
//! Mitsuba 3.9.1 has no fractional crop: `Film` reads the crop window as unsigned integers and
//! throws when `crop_offset + crop_size > size` (`src/render/film.cpp`, `set_crop_window`). So
//! the rounding is ours to define, once: the box is the smallest set of whole pixels that
//! covers the region (first pixel `floor(x0·w)`, one past the last `ceil(x1·w)`), at least one
//! pixel wide and inside the film, which Mitsuba always accepts. Products within 1e-9 pixels of
//! an integer count as that integer, so a fraction written in decimal (0.35 is not exact in
//! binary) lands on the pixel its exact value names.

/// Whole-pixel box `[x0, x1) × [y0, y1)` of a film.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelBox {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl PixelBox {
    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }

    /// Number of pixels.
    pub fn area(&self) -> u64 {
        self.width() as u64 * self.height() as u64
    }
}

/// Tolerance (in pixels) within which `fraction × size` counts as a whole pixel edge.
const SNAP: f64 = 1e-9;

fn edge(fraction: f64, size: u32, up: bool) -> u32 {
    let x = fraction.clamp(0.0, 1.0) * size as f64;
    let r = x.round();
    let x = if (x - r).abs() <= SNAP * size.max(1) as f64 { r } else { x };
    (if up { x.ceil() } else { x.floor() }) as u32
}

/// The pixel box of `rect = [x0, y0, x1, y1]` (fractions of the film) on a `width × height`
/// film (both ≥ 1): the covered pixels, at least one, never past the film's edge.
pub fn pixel_box(width: u32, height: u32, rect: [f64; 4]) -> PixelBox {
    let (width, height) = (width.max(1), height.max(1));
    let x0 = edge(rect[0], width, false).min(width - 1);
    let y0 = edge(rect[1], height, false).min(height - 1);
    let x1 = edge(rect[2], width, true).clamp(x0 + 1, width);
    let y1 = edge(rect[3], height, true).clamp(y0 + 1, height);
    PixelBox { x0, y0, x1, y1 }
}
