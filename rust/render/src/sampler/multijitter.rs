//! Mitsuba's `multijitter` sampler (`src/samplers/multijitter.cpp`, Kensler's correlated
//! multi-jittered sampling): x·y samples on an x × y grid; in 2-D each sample takes a cell and,
//! within it, the sub-stratum that makes both 1-D projections stratified.

use super::random::permute_kensler;
use super::stream::Stream;
use glam::Vec2;

/// Mitsuba `MultijitterSampler::set_sample_count`: (x, y) with y = ⌊√spp⌋ computed in f32
/// and x = ⌈spp / y⌉.
fn resolution(spp: u32) -> (u32, u32) {
    let y = ((spp as f32).sqrt() as u32).max(1);
    (spp.div_ceil(y).max(1), y)
}

/// The sample count of `spp`: x·y (saturating at `u32::MAX`).
pub(super) fn count(spp: u32) -> u32 {
    let (x, y) = resolution(spp);
    (x as u64 * y as u64).min(u32::MAX as u64) as u32
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Multijitter {
    res_x: u32,
    res_y: u32,
    /// Samples in the sequence.
    count: u32,
}

impl Multijitter {
    pub fn new(spp: u32) -> Self {
        let (res_x, res_y) = resolution(spp);
        Multijitter { res_x, res_y, count: count(spp) }
    }

    /// `MultijitterSampler::next_1d`.
    #[inline]
    pub fn next_1d(self, st: &mut Stream) -> f32 {
        let ps = st.perm_seed.wrapping_add(st.next_dim());
        let p = permute_kensler(st.index, self.count, ps.wrapping_mul(0x45fb_e943)) as f32;
        (p + st.jitter()) * (1.0 / self.count as f32)
    }

    /// `MultijitterSampler::next_2d`: a cell of the x × y grid, and within it the sub-stratum
    /// that makes both 1-D projections stratified.
    #[inline]
    pub fn next_2d(self, st: &mut Stream) -> Vec2 {
        let ps = st.perm_seed.wrapping_add(st.next_dim());
        let (rx, ry) = (self.res_x, self.res_y);
        let s = permute_kensler(st.index, self.count, ps.wrapping_mul(0x5163_3e2d));
        let y = s / rx;
        let x = s - y * rx;
        let sx = permute_kensler(x, rx, ps.wrapping_mul(0x68bc_21eb));
        let sy = permute_kensler(y, ry, ps.wrapping_mul(0x02e5_be93));
        let jx = st.jitter();
        let jy = st.jitter();
        let (inv_x, inv_y) = (1.0 / rx as f32, 1.0 / ry as f32);
        // Fused as Mitsuba's build fuses them (bit-identical results).
        Vec2::new((sy as f32 + jx).mul_add(inv_y, x as f32) * inv_x, (sx as f32 + jy).mul_add(inv_x, y as f32) * inv_y)
    }
}
