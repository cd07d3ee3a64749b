//! The film: Mitsuba's `hdrfilm` with `pixel_format = "rgb"`, weighting samples as `scalar_rgb` does
//! by default or as its JIT variants do ([`SplatWeights`])
//! (`src/films/hdrfilm.cpp`, `src/render/film.cpp`, `src/render/imageblock.cpp`; §6, §12).
//!
//! Rendering goes tile by tile: [`Film::tiles`] cuts the crop window into tiles,
//! [`Film::new_block`] gives a thread its own [`ImageBlock`] (tile + filter border), the
//! thread calls [`ImageBlock::put`] for each sample of each pixel **in its tile**, and
//! [`Film::put_block`] adds the block into the film. The film stores only the crop window,
//! so splat weight that falls outside the crop is dropped, as in Mitsuba
//! (`sample_border = false`): every pixel is the weighted average of in-crop samples only,
//! and a constant image stays exactly constant up to its edges.
//!
//! [`Film`] reads `hdrfilm`'s properties ([`FromProps`]); each reconstruction filter reads its
//! own in `filter.rs`.

mod block;
mod filter;
mod image;

pub use block::{ImageBlock, Tile};
pub use filter::{FILTER_RESOLUTION, FilterTable, GAUSSIAN_FIT, ReconstructionFilter, SplatWeights};
pub use image::Image;

use crate::load::props::{FromProps, PluginProps};
use glam::Vec3;
use matte_scene_file::SceneError;

/// The rendered sub-rectangle of the film, in full-film pixels (`crop_offset_x/y`,
/// `crop_width/height`). The camera projection always uses the full film.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CropWindow {
    pub offset: [u32; 2],
    pub size: [u32; 2],
}

/// Accumulated (Σw·R, Σw·G, Σw·B, Σw) over the crop window.
#[derive(Clone, Debug)]
pub struct Film {
    width: u32,
    height: u32,
    crop: CropWindow,
    filter: ReconstructionFilter,
    weights: SplatWeights,
    pixels: Vec<[f32; 4]>,
}

impl FromProps for Film {
    /// `<film type="hdrfilm">` (`src/films/hdrfilm.cpp`, the `Film` base class) with its nested
    /// `<rfilter>` (default: Gaussian, σ = 0.5).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        // Mitsuba's defaults are `is_m_film ? 1 : 768` and `… : 576`: an hdrfilm is not an m-film.
        let width = p.integer_or("width", 768, 1..=1 << 16)? as u32;
        let height = p.integer_or("height", 576, 1..=1 << 16)? as u32;
        let crop = crop_window(p, width, height)?;
        // Output format properties only affect files Mitsuba writes; matte always writes RGB float.
        let pf = p.string("pixel_format")?.to_lowercase();
        if pf != "rgb" && pf != "rgba" {
            return Err(p.prop_err("pixel_format", format!("\"{pf}\" is not supported (rgb or rgba)")));
        }
        let _ = p.string("component_format")?;
        let _ = p.string("file_format")?;
        if p.boolean("sample_border")? {
            return Err(p.prop_err("sample_border", "= true is not supported"));
        }
        let filter = p.nested_rfilter()?;
        // An unused property is reported before an invalid crop window.
        p.object().check_all_used()?;
        Film::new(width, height, crop, filter.unwrap_or_default()).map_err(|e| p.err(e))
    }
}

/// The crop window, if any crop property is given. Mitsuba (src/render/film.cpp):
/// crop_width/height default to the FULL film size, not to what is left after the offset, so
/// an offset alone is an invalid crop window (docs/renderer-semantics.md §6).
fn crop_window(p: &mut PluginProps, width: u32, height: u32) -> Result<Option<CropWindow>, SceneError> {
    if !["crop_offset_x", "crop_offset_y", "crop_width", "crop_height"].iter().any(|n| p.has_property(n)) {
        return Ok(None);
    }
    let ox = p.integer("crop_offset_x", 0..=u32::MAX as i64)? as u32;
    let oy = p.integer("crop_offset_y", 0..=u32::MAX as i64)? as u32;
    let w = p.integer_or("crop_width", width as i64, 1..=u32::MAX as i64)? as u32;
    let h = p.integer_or("crop_height", height as i64, 1..=u32::MAX as i64)? as u32;
    Ok(Some(CropWindow { offset: [ox, oy], size: [w, h] }))
}

impl Film {
    /// A `width`×`height` film rendering `crop` (default: all of it) with `filter`.
    /// Errors: zero size, a crop window that is empty or reaches outside the film (Mitsuba:
    /// "Invalid crop window specification"), invalid filter parameters.
    pub fn new(
        width: u32,
        height: u32,
        crop: Option<CropWindow>,
        filter: ReconstructionFilter,
    ) -> Result<Film, String> {
        if width == 0 || height == 0 {
            return Err(format!("invalid film size {width}x{height}: width and height must be positive"));
        }
        let crop = crop.unwrap_or(CropWindow { offset: [0, 0], size: [width, height] });
        let [ox, oy] = crop.offset.map(u64::from);
        let [cw, ch] = crop.size.map(u64::from);
        if cw == 0 || ch == 0 || ox + cw > width as u64 || oy + ch > height as u64 {
            return Err(format!(
                "invalid crop window: offset ({ox}, {oy}) + size ({cw}, {ch}) must be non-empty and lie within the film ({width}, {height})"
            ));
        }
        filter.validate()?;
        let pixels = vec![[0.0; 4]; (cw * ch) as usize];
        Ok(Film { width, height, crop, filter, weights: SplatWeights::default(), pixels })
    }

    /// Full film width (the camera's aspect uses it, not the crop).
    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    pub fn crop(&self) -> CropWindow {
        self.crop
    }

    pub fn filter(&self) -> ReconstructionFilter {
        self.filter
    }

    /// How samples are weighted: the step table (the default, as Mitsuba's scalar variants)
    /// or the exact kernel (as its JIT variants).
    pub fn splat_weights(&self) -> SplatWeights {
        self.weights
    }

    /// This film weighting its samples by `weights`.
    pub fn with_splat_weights(self, weights: SplatWeights) -> Film {
        Film { weights, ..self }
    }

    /// Rectangles of at most `tile_size`² pixels (full-film coordinates) that cover the crop
    /// window exactly once, row by row. A `tile_size` of 0 is treated as 1.
    pub fn tiles(&self, tile_size: u32) -> Vec<Tile> {
        let ts = tile_size.max(1);
        let [ox, oy] = self.crop.offset;
        let [cw, ch] = self.crop.size;
        let mut tiles = Vec::new();
        for y in (0..ch).step_by(ts as usize) {
            for x in (0..cw).step_by(ts as usize) {
                tiles.push(Tile { offset: [ox + x, oy + y], size: [ts.min(cw - x), ts.min(ch - y)] });
            }
        }
        tiles
    }

    /// A zeroed block for `tile`, with room for the filter border around it.
    pub fn new_block(&self, tile: &Tile) -> ImageBlock {
        ImageBlock::new(*tile, &self.filter, self.weights)
    }

    /// Adds a block's sums into the film; the parts outside the crop window are dropped.
    pub fn put_block(&mut self, block: &ImageBlock) {
        let ([bx, by], [bw, bh]) = block.extent();
        let [ox, oy] = self.crop.offset.map(i64::from);
        let [cw, ch] = self.crop.size.map(i64::from);
        // Block rows/columns that land inside the crop.
        let x0 = (ox - bx).max(0);
        let x1 = (ox + cw - bx).min(bw as i64);
        let y0 = (oy - by).max(0);
        let y1 = (oy + ch - by).min(bh as i64);
        if x0 >= x1 || y0 >= y1 {
            return;
        }
        let src = block.pixels();
        let n = (x1 - x0) as usize;
        for y in y0..y1 {
            let s = (y * bw as i64 + x0) as usize;
            let d = ((by + y - oy) * cw + (bx + x0 - ox)) as usize;
            for (a, b) in self.pixels[d..d + n].iter_mut().zip(&src[s..s + n]) {
                *a = [a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3]];
            }
        }
    }

    /// The crop-sized image: Σw·L / Σw per pixel, 0 where no weight arrived.
    pub fn develop(&self) -> Image {
        let pixels = self
            .pixels
            .iter()
            .map(|p| if p[3] != 0.0 { Vec3::new(p[0], p[1], p[2]) / p[3] } else { Vec3::ZERO })
            .collect();
        Image { width: self.crop.size[0], height: self.crop.size[1], pixels }
    }

    /// Sets all sums back to zero.
    pub fn clear(&mut self) {
        self.pixels.fill([0.0; 4]);
    }
}
