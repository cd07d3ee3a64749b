//! Per-thread accumulation tile: Mitsuba's `ImageBlock` with `normalize = false`,
//! `border = true` (`src/render/imageblock.cpp`, `ImageBlock::put`; §6), weighting samples
//! as its scalar or its JIT variants do ([`SplatWeights`]).
//!
//! A block covers its tile plus the filter border on every side, so a sample taken inside the
//! tile can splat its full footprint without synchronisation. The film later adds the block
//! into its crop-sized storage and drops whatever falls outside the crop ([`super::Film`]).

use super::filter::{FilterTable, ReconstructionFilter, SplatWeights};
use glam::{Vec2, Vec3, Vec4};

/// A rectangle of the crop window, in full-film pixel coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Tile {
    pub offset: [u32; 2],
    pub size: [u32; 2],
}

/// Weighted sums (Σw·R, Σw·G, Σw·B, Σw) for the pixels of one tile and its border.
#[derive(Clone, Debug)]
pub struct ImageBlock {
    tile: Tile,
    border: u32,
    /// Full-film coordinates of storage pixel (0, 0): the tile offset minus the border.
    origin: [i64; 2],
    /// Storage size: tile size + 2·border.
    size: [u32; 2],
    pixels: Vec<[f32; 4]>,
    /// `None` = box filter fast path.
    kernel: Option<Kernel>,
}

/// The filter (exact and discretised) plus scratch space for one sample's weights (so `put`
/// never allocates).
#[derive(Clone, Debug)]
struct Kernel {
    filter: ReconstructionFilter,
    table: FilterTable,
    weights: SplatWeights,
    weights_x: Vec<f32>,
    weights_y: Vec<f32>,
}

impl ImageBlock {
    pub(crate) fn new(tile: Tile, filter: &ReconstructionFilter, weights: SplatWeights) -> ImageBlock {
        let border = filter.border_size();
        let size = [tile.size[0] + 2 * border, tile.size[1] + 2 * border];
        let origin = [tile.offset[0] as i64 - border as i64, tile.offset[1] as i64 - border as i64];
        let kernel = match filter {
            ReconstructionFilter::Box => None,
            _ => {
                let table = filter.table();
                // A footprint spans at most floor(2r) + 1 pixels per axis.
                let n = (2.0 * table.radius()).ceil() as usize + 2;
                Some(Kernel { filter: *filter, table, weights, weights_x: vec![0.0; n], weights_y: vec![0.0; n] })
            }
        };
        let pixels = vec![[0.0; 4]; size[0] as usize * size[1] as usize];
        ImageBlock { tile, border, origin, size, pixels, kernel }
    }

    /// The tile whose samples this block takes.
    pub fn tile(&self) -> Tile {
        self.tile
    }

    /// Resets all sums to zero (blocks are reused across tiles of the same size).
    pub fn clear(&mut self) {
        self.pixels.fill([0.0; 4]);
    }

    /// Adds one radiance sample taken at `film_pos` (full-film pixel coordinates, pixel
    /// (i, j) spans [i, i+1) × [j, j+1), its centre at +0.5).
    ///
    /// Box: the pixel containing the sample gets (rgb, 1). Mitsuba passes the integer pixel
    /// position here rather than px + ξ (`SamplingIntegrator::render_sample`), because in f32
    /// px + ξ can round up to px + 1 for large px; a renderer using the box filter should
    /// likewise pass the pixel's own coordinates (e.g. px + 0.5). Other filters: every pixel i with
    /// `|i + 0.5 − f| ≤ r` on both axes gets weight `k(i + 0.5 − f_x) · k(j + 0.5 − f_y)`,
    /// clipped to the block, with `k` the step table or the exact kernel ([`SplatWeights`]). The offsets are formed as in Mitsuba (first offset, then +1 per
    /// pixel, in f32) so table bins are picked identically. A non-finite position is ignored;
    /// a NaN radiance is accumulated (and poisons the pixel) exactly as in Mitsuba, which only
    /// warns about it.
    #[inline]
    pub fn put(&mut self, film_pos: Vec2, rgb: Vec3) {
        if !film_pos.is_finite() {
            return;
        }
        let (w, h) = (self.size[0] as i64, self.size[1] as i64);
        let Some(kernel) = &mut self.kernel else {
            let x = (film_pos.x.floor() as i64).saturating_sub(self.origin[0]);
            let y = (film_pos.y.floor() as i64).saturating_sub(self.origin[1]);
            if (0..w).contains(&x) && (0..h).contains(&y) {
                let p = &mut self.pixels[(y * w + x) as usize];
                *p = [p[0] + rgb.x, p[1] + rgb.y, p[2] + rgb.z, p[3] + 1.0];
            }
            return;
        };
        // Position in storage pixel units, relative to pixel centres.
        let shift = Vec2::new(
            (self.border as i64 - self.tile.offset[0] as i64) as f32,
            (self.border as i64 - self.tile.offset[1] as i64) as f32,
        ) - 0.5;
        let pos = film_pos + shift;
        let r = kernel.table.radius();
        let lo = ((pos - r).ceil()).max(Vec2::ZERO);
        let hi = ((pos + r).floor()).min(Vec2::new((w - 1) as f32, (h - 1) as f32));
        if lo.x > hi.x || lo.y > hi.y {
            return;
        }
        let (x0, y0) = (lo.x as usize, lo.y as usize);
        // min(): f32 rounding of far-away positions must not overrun the scratch space.
        let nx = ((hi.x - lo.x) as usize + 1).min(kernel.weights_x.len());
        let ny = ((hi.y - lo.y) as usize + 1).min(kernel.weights_y.len());
        let (wx, wy) = (&mut kernel.weights_x[..nx], &mut kernel.weights_y[..ny]);
        let rel = lo - pos;
        // The choice of weights is made once per sample, not per weight.
        match kernel.weights {
            SplatWeights::Discretized => {
                fill_weights(wx, rel.x, |x| kernel.table.eval(x));
                fill_weights(wy, rel.y, |x| kernel.table.eval(x));
            }
            SplatWeights::Exact => {
                fill_weights(wx, rel.x, |x| kernel.filter.eval(x));
                fill_weights(wy, rel.y, |x| kernel.filter.eval(x));
            }
        }
        // (R, G, B, 1)·w added as one 4-wide operation per pixel: the same products and sums
        // as channel by channel.
        let rgbw = Vec4::new(rgb.x, rgb.y, rgb.z, 1.0);
        for (j, &fy) in wy.iter().enumerate() {
            let row = (y0 + j) * w as usize + x0;
            for (p, &fx) in self.pixels[row..row + nx].iter_mut().zip(wx.iter()) {
                *p = (Vec4::from_array(*p) + rgbw * (fx * fy)).to_array();
            }
        }
    }

    /// Full-film coordinates of storage pixel (0, 0) and the storage size (tile + border).
    pub(crate) fn extent(&self) -> ([i64; 2], [u32; 2]) {
        (self.origin, self.size)
    }

    pub(crate) fn pixels(&self) -> &[[f32; 4]] {
        &self.pixels
    }
}

/// The weights `k(first)`, `k(first + 1)`, … (offsets formed by adding 1 in f32, as Mitsuba).
#[inline(always)]
fn fill_weights(out: &mut [f32], first: f32, k: impl Fn(f32) -> f32) {
    let mut x = first;
    for v in out {
        *v = k(x);
        x += 1.0;
    }
}
