//! Mitsuba's `orthogonal` sampler (`src/samplers/orthogonal.cpp`): r² samples (r the smallest
//! prime ≥ 2 with r² ≥ `sample_count`), rows of an orthogonal array of the given `strength`:
//! the Bose construction for strength 2, Bush's for any other; its `next_2d` is two `next_1d`.

use super::random::permute_kensler;
use super::stream::Stream;
use glam::Vec2;

/// Mitsuba `OrthogonalSampler::set_sample_count`: the smallest prime r ≥ 2 with r² ≥ spp.
fn resolution(spp: u32) -> u32 {
    let is_prime = |x: u64| (2..=x / 2).take_while(|i| i * i <= x).all(|i| !x.is_multiple_of(i));
    let mut r = 2u64;
    while r * r < spp as u64 || !is_prime(r) {
        r += 1;
    }
    r as u32
}

/// The sample count of `spp`: r² (saturating at `u32::MAX`).
pub(super) fn count(spp: u32) -> u32 {
    (resolution(spp) as u64).pow(2).min(u32::MAX as u64) as u32
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Orthogonal {
    /// r.
    res: u32,
    strength: u32,
    /// Samples in the sequence.
    count: u32,
}

impl Orthogonal {
    pub fn new(spp: u32, strength: u32) -> Self {
        Orthogonal { res: resolution(spp), strength, count: count(spp) }
    }

    /// `OrthogonalSampler::next_1d`: the next dimension of the array's row.
    #[inline]
    pub fn next_1d(self, st: &mut Stream) -> f32 {
        let j = st.next_dim();
        if self.strength == 2 { self.bose(st, j) } else { self.bush(st, j) }
    }

    /// `OrthogonalSampler::next_2d`: two `next_1d`.
    #[inline]
    pub fn next_2d(self, st: &mut Stream) -> Vec2 {
        let x = self.next_1d(st);
        Vec2::new(x, self.next_1d(st))
    }

    /// Mitsuba `OrthogonalSampler::bose`: dimension `j` of the Bose orthogonal array
    /// OA(r², r + 1, r, 2) row of the permuted sample index (columns a₀, a₁, a₀ + (j−1)·a₁
    /// mod r), stratum and sub-stratum from column j and its partner column, each permuted.
    fn bose(self, st: &mut Stream, j: u32) -> f32 {
        let r = self.res;
        let p = st.perm_seed;
        let i = permute_kensler(st.index % self.count, self.count, p);
        let a0 = i / r;
        let a1 = i - a0 * r;
        let k = if !j.is_multiple_of(2) { j.wrapping_sub(1) } else { j.wrapping_add(1) };
        let (a_ij, a_ik) = match j {
            0 => (a0, a1),
            1 => (a1, a0),
            _ => (
                a0.wrapping_add(j.wrapping_sub(1).wrapping_mul(a1)) % r,
                a0.wrapping_add(k.wrapping_sub(1).wrapping_mul(a1)) % r,
            ),
        };
        let pj = p.wrapping_mul(j.wrapping_add(1));
        let stratum = permute_kensler(a_ij, r, pj.wrapping_mul(0x5163_3e2d));
        let sub = permute_kensler(a_ik, r, pj.wrapping_mul(0x68bc_21eb));
        let jitter = st.jitter();
        (stratum as f32 + (sub as f32 + jitter) / r as f32) / r as f32
    }

    /// Mitsuba `OrthogonalSampler::bush` (strength s ≠ 2): the permuted index among r^s rows,
    /// its digits as polynomial coefficients evaluated at `j`. Mitsuba's digit extraction
    /// (`to_base_s`) puts `i·(1 − r)` (wrapping) in the constant term and shifts the base-r
    /// digits up by one; matte computes the same numbers. r^s saturates at `u32::MAX`.
    fn bush(self, st: &mut Stream, j: u32) -> f32 {
        let (r, s) = (self.res, self.strength);
        let p = st.perm_seed;
        let n = r.checked_pow(s).unwrap_or(u32::MAX);
        let stm = (n / r).max(1);
        let i = permute_kensler(st.index, n, p);
        // to_base_s, as Mitsuba computes it.
        let mut phi = 0u32;
        let mut digits = [0u32; 32];
        let (mut cur, mut tmp) = (i, i);
        for d in digits.iter_mut().take(s as usize) {
            *d = tmp.wrapping_sub(cur.wrapping_mul(r));
            tmp = cur;
            cur /= r;
        }
        for &d in digits[..s as usize].iter().rev() {
            phi = phi.wrapping_mul(j).wrapping_add(d);
        }
        let pj = p.wrapping_mul(j.wrapping_add(1));
        let stratum = permute_kensler(phi % r, r, pj.wrapping_mul(0x5163_3e2d));
        let sub = permute_kensler((i / r) % stm, stm, pj.wrapping_mul(0x68bc_21eb));
        let jitter = st.jitter();
        (stratum as f32 + (sub as f32 + jitter) / stm as f32) / r as f32
    }
}
