//! The state a sampler draws from within one pixel's sequence: the PCG32 generator (Mitsuba's
//! `PCG32Sampler`), the permutation seed of the sequence, the index of the current sample and
//! of its next dimension (Mitsuba's `m_sample_index`, `m_dimension_index`), and whether strata
//! are jittered.

use matte_brdf::rng::Pcg32;

#[derive(Clone, Debug)]
pub(super) struct Stream {
    pub rng: Pcg32,
    /// Jitter within a stratum (`jitter`), or take its centre.
    pub jitter: bool,
    /// The per-sequence permutation (scramble) seed.
    pub perm_seed: u32,
    /// Index of the current sample within the sequence.
    pub index: u32,
    /// Index of the next dimension of the current sample.
    pub dim: u32,
}

impl Stream {
    /// Sample 0, dimension 0.
    pub fn new(rng: Pcg32, jitter: bool, perm_seed: u32) -> Self {
        Stream { rng, jitter, perm_seed, index: 0, dim: 0 }
    }

    /// Uniform in [0, 1) from the generator.
    #[inline]
    pub fn rng_1d(&mut self) -> f32 {
        self.rng.next_f32()
    }

    /// The jitter within a stratum: a PCG32 number, or ½ without `jitter`.
    #[inline]
    pub fn jitter(&mut self) -> f32 {
        if self.jitter { self.rng_1d() } else { 0.5 }
    }

    /// The next dimension's index (then counts it).
    #[inline]
    pub fn next_dim(&mut self) -> u32 {
        let d = self.dim;
        self.dim = self.dim.wrapping_add(1);
        d
    }
}
