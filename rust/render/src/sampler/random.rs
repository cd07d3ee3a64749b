//! The hashes and permutations the samplers share: Mitsuba's `sample_tea_32`,
//! `permute_kensler` and `permute` (here [`permute_pow2`]) from `include/mitsuba/core/random.h`,
//! and matte's own seed finaliser ([`splitmix64`]), which derives each pixel's stream and
//! sequence seed from the sampler's `seed`.

/// The Tiny Encryption Algorithm as Mitsuba's `sample_tea_32` (`include/mitsuba/core/random.h`;
/// Zafar, Olano and Curtis, "GPU Random Numbers via the Tiny Encryption Algorithm").
#[inline]
pub fn sample_tea_32(mut v0: u32, mut v1: u32, rounds: u32) -> (u32, u32) {
    let mut sum = 0u32;
    for _ in 0..rounds {
        sum = sum.wrapping_add(0x9e37_79b9);
        v0 = v0.wrapping_add(
            ((v1 << 4).wrapping_add(0xa341_316c)) ^ v1.wrapping_add(sum) ^ ((v1 >> 5).wrapping_add(0xc801_3ea4)),
        );
        v1 = v1.wrapping_add(
            ((v0 << 4).wrapping_add(0xad90_777d)) ^ v0.wrapping_add(sum) ^ ((v0 >> 5).wrapping_add(0x7e95_761e)),
        );
    }
    (v0, v1)
}

/// Element `index` of a pseudorandom permutation of [0, n) (Kensler, "Correlated
/// Multi-Jittered Sampling", Pixar technical memo 13-01, 2013: a hash on the next power of
/// two, cycle-walked into range), as Mitsuba's `permute_kensler`. Indices ≥ n map into
/// [0, n) too.
#[inline]
pub fn permute_kensler(index: u32, n: u32, seed: u32) -> u32 {
    if n <= 1 {
        return 0;
    }
    let mut w = n - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    let mut i = index;
    loop {
        i ^= seed;
        i = i.wrapping_mul(0xe170_893d);
        i ^= seed >> 16;
        i ^= (i & w) >> 4;
        i ^= seed >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= seed >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | seed >> 27);
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= w;
        i ^= i >> 5;
        if i < n {
            break;
        }
    }
    i.wrapping_add(seed) % n
}

/// Element `index` of a pseudorandom permutation of [0, n), n a power of two: a shuffle
/// network flipping bit `l` when a 2-round TEA hash of (index | 2^l, seed) has it set
/// (Mitsuba's `permute`).
#[inline]
pub fn permute_pow2(mut index: u32, n: u32, seed: u32) -> u32 {
    for level in 0..n.trailing_zeros() {
        let bit = 1u32 << level;
        if sample_tea_32(index | bit, seed, 2).0 & bit == bit {
            index ^= bit;
        }
    }
    index
}

/// SplitMix64 finaliser: decorrelates nearby seeds and pixel indices.
#[inline]
pub(super) fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}
