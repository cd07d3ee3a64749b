//! Mitsuba's `ldsampler` (`src/samplers/ldsampler.cpp`): r² samples (r the next power of two
//! ≥ 2 with r² ≥ `sample_count`) of a (0, 2)-sequence: van der Corput and Sobol' (Mitsuba's
//! `include/mitsuba/core/qmc.h`) of the permuted sample index, scrambled per sequence.

use super::random::{permute_pow2, sample_tea_32};
use super::stream::Stream;
use glam::Vec2;

/// Mitsuba `LowDiscrepancySampler::set_sample_count`: r = 2, then r = next power of two
/// above r while r² < spp.
fn resolution(spp: u32) -> u32 {
    let mut r = 2u64;
    while r * r < spp as u64 {
        r = (r + 1).next_power_of_two();
    }
    r as u32
}

/// The sample count of `spp`: r² (saturating at `u32::MAX`).
pub(super) fn count(spp: u32) -> u32 {
    (resolution(spp) as u64).pow(2).min(u32::MAX as u64) as u32
}

#[derive(Clone, Copy, Debug)]
pub(super) struct LowDiscrepancy {
    /// Samples in the sequence.
    count: u32,
}

impl LowDiscrepancy {
    pub fn new(spp: u32) -> Self {
        LowDiscrepancy { count: count(spp) }
    }

    /// `LowDiscrepancySampler::next_1d`.
    #[inline]
    pub fn next_1d(self, st: &mut Stream) -> f32 {
        let ps = st.perm_seed.wrapping_add(st.next_dim());
        let i = permute_pow2(st.index, self.count, ps);
        radical_inverse_2(i, sample_tea_32(st.perm_seed, 0x48bc_48eb, 4).0)
    }

    /// `LowDiscrepancySampler::next_2d`: the (0, 2)-sequence (van der Corput, Sobol') of the
    /// permuted index, scrambled per sequence.
    #[inline]
    pub fn next_2d(self, st: &mut Stream) -> Vec2 {
        let ps = st.perm_seed.wrapping_add(st.next_dim());
        let i = permute_pow2(st.index, self.count, ps);
        let (sx, sy) = sample_tea_32(st.perm_seed, 0x98bc_51ab, 4);
        Vec2::new(radical_inverse_2(i, sx), sobol_2(i, sy))
    }
}

/// The scrambled base-2 radical inverse (van der Corput) of `index`, 23 bits, as Mitsuba's
/// `radical_inverse_2` in single precision (`include/mitsuba/core/qmc.h`).
#[inline]
pub fn radical_inverse_2(index: u32, scramble: u32) -> f32 {
    f32::from_bits(((index.reverse_bits() ^ scramble) >> 9) | 0x3f80_0000) - 1.0
}

/// The scrambled second Sobol' dimension of `index`, as Mitsuba's `sobol_2` in single
/// precision. Mitsuba converts the 32-bit result to f32 and divides by 2³², which rounds to
/// exactly 1 for results ≥ 2³² − 128 (probability 2⁻²⁵); matte returns the largest f32 below 1
/// there, as every warp expects [0, 1).
#[inline]
pub fn sobol_2(mut index: u32, mut scramble: u32) -> f32 {
    let mut v = 1u32 << 31;
    while index != 0 {
        if index & 1 == 1 {
            scramble ^= v;
        }
        index >>= 1;
        v ^= v >> 1;
    }
    (scramble as f32 / 4_294_967_296.0).min(1.0 - f32::EPSILON / 2.0)
}
