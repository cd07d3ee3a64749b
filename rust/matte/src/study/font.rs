//! Text in the study's figures: DejaVu Sans (`fonts/DejaVuSans.ttf`, Bitstream Vera licence in
//! `fonts/LICENSE`), embedded in the binary. ab_glyph lays out and rasterises the strips' labels
//! anti-aliased; the plots' SVG is laid out with the same font's metrics.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};
use image::{Rgb, RgbImage};
use std::sync::LazyLock;

/// DejaVu Sans Book, the font of matplotlib's figures.
pub static DEJAVU_SANS: &[u8] = include_bytes!("fonts/DejaVuSans.ttf");

static FONT: LazyLock<FontRef<'static>> =
    LazyLock::new(|| FontRef::try_from_slice(DEJAVU_SANS).expect("the embedded font parses"));

/// The glyphs of `text` at `px` pixels per em with their pen positions, baseline at y = 0.
fn layout(text: &str, px: f32) -> (Vec<ab_glyph::Glyph>, f32) {
    let font = FONT.as_scaled(PxScale::from(px));
    let (mut x, mut last) = (0.0, None);
    let mut glyphs = Vec::new();
    for c in text.chars() {
        let id = font.glyph_id(c);
        x += last.map_or(0.0, |l| font.kern(l, id));
        glyphs.push(id.with_scale_and_position(px, point(x, 0.0)));
        x += font.h_advance(id);
        last = Some(id);
    }
    (glyphs, x)
}

/// Advance width of `text` in pixels at `px` pixels per em.
#[must_use]
pub fn width(text: &str, px: f32) -> f32 {
    layout(text, px).1
}

/// Ascent and descent (negative) in pixels at `px` pixels per em.
#[must_use]
pub fn extent(px: f32) -> (f32, f32) {
    let font = FONT.as_scaled(PxScale::from(px));
    (font.ascent(), font.descent())
}

/// `text`, or its longest prefix with "…" that is at most `max` pixels wide at `px`.
#[must_use]
pub fn ellipsize(text: &str, px: f32, max: f32) -> String {
    if width(text, px) <= max {
        return text.to_string();
    }
    let mut cut: String = text.to_string();
    while cut.pop().is_some() {
        let s = format!("{}…", cut.trim_end());
        if width(&s, px) <= max {
            return s;
        }
    }
    String::new()
}

/// Draws `text` anti-aliased in `colour` with its top (the font's ascent) at `top` and its pen
/// starting at `left`.
pub fn draw(img: &mut RgbImage, left: f32, top: f32, text: &str, px: f32, colour: Rgb<u8>) {
    let (glyphs, _) = layout(text, px);
    let baseline = top + extent(px).0;
    for g in glyphs {
        let Some(outline) = FONT.outline_glyph(g) else { continue };
        let b = outline.px_bounds();
        outline.draw(|x, y, coverage| {
            let (x, y) = (b.min.x + left + x as f32, b.min.y + baseline + y as f32);
            if x < 0.0 || y < 0.0 || x >= img.width() as f32 || y >= img.height() as f32 {
                return;
            }
            let p = img.get_pixel_mut(x as u32, y as u32);
            let a = coverage.clamp(0.0, 1.0);
            for (d, s) in p.0.iter_mut().zip(colour.0) {
                *d = (*d as f32 * (1.0 - a) + s as f32 * a).round() as u8;
            }
        });
    }
}
