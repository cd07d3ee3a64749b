//! Mitsuba's `independent` sampler (`src/samplers/independent.cpp`): uniform PCG32 numbers, no
//! stratification. matte gives each pixel its own stream, derived from the sampler's `seed` and
//! the pixel index ([`pixel_rng`]), so an image does not depend on the tiling or the thread
//! count.

use super::random::splitmix64;
use matte_brdf::rng::Pcg32;

/// The generator of pixel `pixel`'s stream: `seed` picks the sequence family, `pixel` the
/// stream.
pub(super) fn pixel_rng(seed: u64, pixel: u64) -> Pcg32 {
    Pcg32::new(splitmix64(seed.wrapping_add(pixel)), splitmix64(pixel ^ splitmix64(seed)))
}
