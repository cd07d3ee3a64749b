//! Mitsuba's `independent` sampler: uniform PCG32 numbers, no stratification
//! (`src/samplers/independent.cpp`). Each pixel gets its own stream derived from the seed
//! and the pixel index, so results do not depend on the tiling or the thread count.

use glam::Vec2;

/// PCG32 (O'Neill 2014, "PCG: A family of simple fast space-efficient statistically good
/// algorithms for random number generation"), the generator Mitsuba uses.
#[derive(Clone, Debug)]
pub struct Sampler {
    state: u64,
    inc: u64,
}

const MULT: u64 = 0x5851_f42d_4c95_7f2d;

impl Sampler {
    /// A stream for one pixel: `seed` picks the sequence family, `pixel` the stream.
    pub fn for_pixel(seed: u64, pixel: u64) -> Self {
        let mut s = Sampler { state: 0, inc: (splitmix64(pixel ^ splitmix64(seed)) << 1) | 1 };
        s.next_u32();
        s.state = s.state.wrapping_add(splitmix64(seed.wrapping_add(pixel)));
        s.next_u32();
        s
    }

    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(MULT).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// Uniform in [0, 1) (23 random mantissa bits, as Mitsuba's `next_float32`).
    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        f32::from_bits((self.next_u32() >> 9) | 0x3f80_0000) - 1.0
    }

    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        let x = self.next_1d();
        Vec2::new(x, self.next_1d())
    }
}

/// SplitMix64 finaliser: decorrelates nearby seeds and pixel indices.
#[inline]
fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}
