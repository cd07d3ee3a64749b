//! The random number generator the tests, the benchmarks and the renderer's samplers share.

/// PCG32 (O'Neill 2014, "PCG: A family of simple fast space-efficient statistically good
/// algorithms for random number generation"), the generator Mitsuba's samplers use (Dr.Jit's
/// `PCG32`); [`Pcg32::new`] seeds as its `seed(initstate, initseq)`.
#[derive(Clone, Debug)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

impl Pcg32 {
    /// The generator of stream `stream` started at `seed`.
    #[must_use]
    pub fn new(seed: u64, stream: u64) -> Self {
        let mut r = Pcg32 { state: 0, inc: (stream << 1) | 1 };
        r.next_u32();
        r.state = r.state.wrapping_add(seed);
        r.next_u32();
        r
    }

    /// The next 32 random bits.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(MULT).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// Uniform in [0, 1) with 23 random mantissa bits (Mitsuba's `next_float32`).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        f32::from_bits((self.next_u32() >> 9) | 0x3f80_0000) - 1.0
    }
}

/// PCG32's multiplier.
const MULT: u64 = 0x5851_f42d_4c95_7f2d;
