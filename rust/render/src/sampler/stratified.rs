//! Mitsuba's `stratified` sampler (`src/samplers/stratified.cpp`): r² samples (r the smallest
//! with r² ≥ `sample_count`); dimension d of sample i is stratum `permute_kensler(i)` of r²
//! (1-D) or of the r × r grid (2-D), jittered within it.

use super::random::permute_kensler;
use super::stream::Stream;
use glam::Vec2;

/// Mitsuba `StratifiedSampler::set_sample_count`: the smallest r with r² ≥ spp.
fn resolution(spp: u32) -> u32 {
    let mut r = (spp as f64).sqrt() as u64;
    while r * r < spp as u64 {
        r += 1;
    }
    while r > 1 && (r - 1) * (r - 1) >= spp as u64 {
        r -= 1;
    }
    r.max(1) as u32
}

/// The sample count of `spp`: r² (saturating at `u32::MAX`).
pub(super) fn count(spp: u32) -> u32 {
    (resolution(spp) as u64).pow(2).min(u32::MAX as u64) as u32
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Stratified {
    /// r.
    res: u32,
    /// Samples in the sequence.
    count: u32,
}

impl Stratified {
    pub fn new(spp: u32) -> Self {
        Stratified { res: resolution(spp), count: count(spp) }
    }

    /// Mitsuba `StratifiedSampler::next_1d`.
    #[inline]
    pub fn next_1d(self, st: &mut Stream) -> f32 {
        let p = permute_kensler(st.index, self.count, st.perm_seed.wrapping_add(st.next_dim()));
        (p as f32 + st.jitter()) * (1.0 / self.count as f32)
    }

    /// Mitsuba `StratifiedSampler::next_2d`: one of r × r cells, jittered.
    #[inline]
    pub fn next_2d(self, st: &mut Stream) -> Vec2 {
        let p = permute_kensler(st.index, self.count, st.perm_seed.wrapping_add(st.next_dim()));
        let y = p / self.res;
        let x = p - y * self.res;
        let jx = st.jitter();
        let jy = st.jitter();
        let inv = 1.0 / self.res as f32;
        Vec2::new((x as f32 + jx) * inv, (y as f32 + jy) * inv)
    }
}
