//! Mitsuba 3.9.1's samplers (`src/samplers/*.cpp`, docs/renderer-semantics.md §5).
//!
//! * `independent`: uniform PCG32 numbers, no stratification. Each pixel gets its own stream
//!   derived from the seed and the pixel index ([`Sampler::for_pixel`]), so results do not
//!   depend on the tiling or the thread count.
//! * `stratified`, `multijitter`, `orthogonal`, `ldsampler`: each pixel is one sequence of
//!   `sample_count` samples; sample `i`'s dimension `d` (each `next_1d` and each `next_2d` is
//!   one dimension, `orthogonal`'s `next_2d` two) comes from a per-dimension permutation of
//!   the sample indices, seeded from the pixel's sequence seed. Given a sequence seed, these
//!   four produce exactly the numbers of Mitsuba's scalar variants after `sampler.seed(s)`
//!   ([`Sampler::mitsuba`], checked against live Mitsuba in `tests/render/samplers.rs`); only the
//!   sequence seed of each pixel differs from Mitsuba's (which counts pixels in its block
//!   spiral).
//!
//! [`Sampling`] reads the sampler plugins' properties ([`FromProps`]).

use crate::load::props::{FromProps, PluginProps};
use glam::Vec2;
use matte_brdf::rng::Pcg32;
use matte_scene_file::SceneError;

/// A sampler plugin with its properties (other than `sample_count` and `seed`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerKind {
    Independent,
    Stratified { jitter: bool },
    Multijitter { jitter: bool },
    Orthogonal { jitter: bool, strength: u32 },
    LowDiscrepancy,
}

impl SamplerKind {
    /// The plugin name.
    pub fn name(self) -> &'static str {
        match self {
            SamplerKind::Independent => "independent",
            SamplerKind::Stratified { .. } => "stratified",
            SamplerKind::Multijitter { .. } => "multijitter",
            SamplerKind::Orthogonal { .. } => "orthogonal",
            SamplerKind::LowDiscrepancy => "ldsampler",
        }
    }

    /// The sample count Mitsuba's `set_sample_count(spp)` makes of `spp` (the constructor
    /// and `render(spp=…)` both call it): `stratified` the next square, `multijitter`
    /// ⌊√spp⌋ (in f32) rows of ⌈spp/rows⌉, `orthogonal` the square of the next prime ≥ 2,
    /// `ldsampler` the square of the next power of two ≥ 2. Saturates at `u32::MAX`.
    pub fn round_sample_count(self, spp: u32) -> u32 {
        let sat = |v: u64| v.min(u32::MAX as u64) as u32;
        match self {
            SamplerKind::Independent => spp,
            SamplerKind::Stratified { .. } => sat((stratified_resolution(spp) as u64).pow(2)),
            SamplerKind::Multijitter { .. } => {
                let (x, y) = multijitter_resolution(spp);
                sat(x as u64 * y as u64)
            }
            SamplerKind::Orthogonal { .. } => sat((orthogonal_resolution(spp) as u64).pow(2)),
            SamplerKind::LowDiscrepancy => sat((ld_resolution(spp) as u64).pow(2)),
        }
    }
}

/// Mitsuba `StratifiedSampler::set_sample_count`: the smallest r with r² ≥ spp.
fn stratified_resolution(spp: u32) -> u32 {
    let mut r = (spp as f64).sqrt() as u64;
    while r * r < spp as u64 {
        r += 1;
    }
    while r > 1 && (r - 1) * (r - 1) >= spp as u64 {
        r -= 1;
    }
    r.max(1) as u32
}

/// Mitsuba `MultijitterSampler::set_sample_count`: (x, y) with y = ⌊√spp⌋ computed in f32
/// and x = ⌈spp / y⌉.
fn multijitter_resolution(spp: u32) -> (u32, u32) {
    let y = ((spp as f32).sqrt() as u32).max(1);
    (spp.div_ceil(y).max(1), y)
}

/// Mitsuba `OrthogonalSampler::set_sample_count`: the smallest prime r ≥ 2 with r² ≥ spp.
fn orthogonal_resolution(spp: u32) -> u32 {
    let is_prime = |x: u64| (2..=x / 2).take_while(|i| i * i <= x).all(|i| !x.is_multiple_of(i));
    let mut r = 2u64;
    while r * r < spp as u64 || !is_prime(r) {
        r += 1;
    }
    r as u32
}

/// Mitsuba `LowDiscrepancySampler::set_sample_count`: r = 2, then r = next power of two
/// above r while r² < spp.
fn ld_resolution(spp: u32) -> u32 {
    let mut r = 2u64;
    while r * r < spp as u64 {
        r = (r + 1).next_power_of_two();
    }
    r as u32
}

/// The sensor's sampler as the renderer uses it: the plugin, the samples per pixel (already
/// rounded as Mitsuba rounds them) and the seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sampling {
    pub kind: SamplerKind,
    /// Samples per pixel, as [`SamplerKind::round_sample_count`] rounds them.
    pub spp: u32,
    pub seed: u64,
}

/// Largest `sample_count` of the stratified samplers (their rounded counts then fit in u32).
const MAX_STRATIFIED_COUNT: i64 = 1 << 30;

impl FromProps for Sampling {
    /// Every sampler reads `sample_count` (default 4) and `seed` (default 0) (`Sampler`,
    /// `src/render/sampler.cpp`); `stratified`, `multijitter` and `orthogonal` read `jitter`
    /// (default true), `orthogonal` `strength` (default 2). The sample count is rounded as the
    /// plugin's `set_sample_count` rounds it.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let plugin = p.object().plugin.as_str();
        let max_count = if plugin == "independent" { u32::MAX as i64 } else { MAX_STRATIFIED_COUNT };
        let kind = match plugin {
            "stratified" => SamplerKind::Stratified { jitter: p.boolean("jitter")? },
            "multijitter" => SamplerKind::Multijitter { jitter: p.boolean("jitter")? },
            "orthogonal" => {
                let jitter = p.boolean("jitter")?;
                SamplerKind::Orthogonal { jitter, strength: p.integer("strength", 1..=32)? as u32 }
            }
            "ldsampler" => SamplerKind::LowDiscrepancy,
            _ => SamplerKind::Independent,
        };
        let spp = p.integer("sample_count", 1..=max_count)? as u32;
        let seed = p.integer("seed", 0..=i64::MAX)? as u64;
        // An unused property is reported before a too large orthogonal array.
        p.object().check_all_used()?;
        let sampling = Sampling::new(kind, spp, seed);
        check_orthogonal_rows(p, sampling)?;
        Ok(sampling)
    }
}

/// `orthogonal`'s array has r^strength rows (r = √spp): more than 2³² is refused.
fn check_orthogonal_rows(p: &PluginProps, sampling: Sampling) -> Result<(), SceneError> {
    if let SamplerKind::Orthogonal { strength, .. } = sampling.kind {
        let r = (sampling.spp as f64).sqrt().round() as u32;
        if strength != 2 && r.checked_pow(strength).is_none() {
            let message = format!(
                "{strength} with sample_count {} needs {r}^{strength} array rows, more than 2^32",
                sampling.spp
            );
            return Err(p.prop_err("strength", message));
        }
    }
    Ok(())
}

impl Sampling {
    /// `spp` rounded for `kind`.
    pub fn new(kind: SamplerKind, spp: u32, seed: u64) -> Self {
        Sampling { kind, spp: kind.round_sample_count(spp), seed }
    }

    /// The `independent` sampler.
    pub fn independent(spp: u32, seed: u64) -> Self {
        Sampling::new(SamplerKind::Independent, spp, seed)
    }

    /// Another sample count, rounded as Mitsuba's `render(spp=…)` rounds it.
    pub fn with_spp(self, spp: u32) -> Self {
        Sampling::new(self.kind, spp, self.seed)
    }

    pub fn with_seed(self, seed: u64) -> Self {
        Sampling { seed, ..self }
    }

    /// The sampler of stream `stream` (a pixel's index, or a particle tracer work item's):
    /// for `independent` exactly [`Sampler::for_pixel`]; for the others Mitsuba's sequence
    /// with a sequence seed hashed from the seed and the stream.
    #[inline]
    pub fn sampler(&self, stream: u64) -> Sampler {
        match self.kind {
            SamplerKind::Independent => Sampler::for_pixel(self.seed, stream),
            kind => Sampler::mitsuba(kind, self.spp, 0, splitmix64(stream ^ splitmix64(self.seed)) as u32),
        }
    }
}

/// Which sequence a [`Sampler`] draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Seq {
    Independent,
    Stratified,
    Multijitter,
    /// `orthogonal` with strength 2 (Bose construction).
    Bose,
    /// `orthogonal` with another strength (Bush construction).
    Bush,
    LowDiscrepancy,
}

/// A per-pixel sample stream: a [`Pcg32`], plus for the stratified samplers the sample and
/// dimension index within the pixel's sequence. The drivers call [`Sampler::advance`] after
/// each sample.
#[derive(Clone, Debug)]
pub struct Sampler {
    rng: Pcg32,
    seq: Seq,
    jitter: bool,
    /// Samples in the sequence.
    count: u32,
    /// Stratification resolution: stratified's and orthogonal's r, multijitter's x.
    res: u32,
    /// Multijitter's y resolution; Bush's strength.
    res2: u32,
    /// The per-sequence permutation (scramble) seed.
    perm_seed: u32,
    /// Index of the current sample within the sequence.
    index: u32,
    /// Index of the next dimension of the current sample.
    dim: u32,
}

/// Dr.Jit's `PCG32_DEFAULT_STREAM`.
const PCG32_DEFAULT_STREAM: u64 = 0xda3e_39cb_94b9_5bdb;

impl Sampler {
    /// The `independent` stream for one pixel: `seed` picks the sequence family, `pixel` the
    /// stream.
    pub fn for_pixel(seed: u64, pixel: u64) -> Self {
        let rng = Pcg32::new(splitmix64(seed.wrapping_add(pixel)), splitmix64(pixel ^ splitmix64(seed)));
        Sampler::blank(rng, Seq::Independent)
    }

    fn blank(rng: Pcg32, seq: Seq) -> Self {
        Sampler { rng, seq, jitter: true, count: 1, res: 1, res2: 1, perm_seed: 0, index: 0, dim: 0 }
    }

    /// Exactly Mitsuba's scalar-variant sampler `kind` with `sample_count` (rounded as
    /// Mitsuba rounds it) and `seed` property `base_seed`, after `sampler.seed(seed)`: PCG32
    /// seeded with (base_seed + seed, the default stream) (`PCG32Sampler::seed`,
    /// `src/render/sampler.cpp`), permutation seed `sample_tea_32(base_seed, seed).0`
    /// (`compute_per_sequence_seed` with one sequence per wavefront).
    pub fn mitsuba(kind: SamplerKind, sample_count: u32, base_seed: u32, seed: u32) -> Self {
        let (n, count) = (sample_count, kind.round_sample_count(sample_count));
        let (seq, jitter, res, res2) = match kind {
            SamplerKind::Independent => (Seq::Independent, true, 1, 1),
            SamplerKind::Stratified { jitter } => (Seq::Stratified, jitter, stratified_resolution(n), 1),
            SamplerKind::Multijitter { jitter } => {
                let (x, y) = multijitter_resolution(n);
                (Seq::Multijitter, jitter, x, y)
            }
            SamplerKind::Orthogonal { jitter, strength: 2 } => (Seq::Bose, jitter, orthogonal_resolution(n), 2),
            SamplerKind::Orthogonal { jitter, strength } => (Seq::Bush, jitter, orthogonal_resolution(n), strength),
            SamplerKind::LowDiscrepancy => (Seq::LowDiscrepancy, false, ld_resolution(n), 1),
        };
        let rng = Pcg32::new(base_seed.wrapping_add(seed) as u64, PCG32_DEFAULT_STREAM);
        let perm_seed = sample_tea_32(base_seed, seed, 4).0;
        Sampler { count, res, res2, jitter, perm_seed, ..Sampler::blank(rng, seq) }
    }

    /// The next 32 random bits of the stream's generator.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        self.rng.next_u32()
    }

    /// Uniform in [0, 1) from the generator.
    #[inline]
    fn rng_1d(&mut self) -> f32 {
        self.rng.next_f32()
    }

    /// The next dimension of the current sample, in [0, 1).
    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        if self.seq == Seq::Independent {
            return self.rng_1d();
        }
        self.sequence_1d()
    }

    /// The next two-dimensional dimension of the current sample, in [0, 1)².
    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        if self.seq == Seq::Independent {
            let x = self.rng_1d();
            return Vec2::new(x, self.rng_1d());
        }
        self.sequence_2d()
    }

    /// Ends the current sample: the next draw is dimension 0 of the next sample (Mitsuba
    /// `Sampler::advance`). The independent stream simply continues.
    #[inline]
    pub fn advance(&mut self) {
        self.index = self.index.wrapping_add(1);
        self.dim = 0;
    }

    /// The jitter within a stratum: a PCG32 number, or ½ without `jitter`.
    #[inline]
    fn jitter(&mut self) -> f32 {
        if self.jitter { self.rng_1d() } else { 0.5 }
    }

    #[inline]
    fn next_dim(&mut self) -> u32 {
        let d = self.dim;
        self.dim = self.dim.wrapping_add(1);
        d
    }

    #[inline(never)]
    fn sequence_1d(&mut self) -> f32 {
        match self.seq {
            // Mitsuba `StratifiedSampler::next_1d`.
            Seq::Stratified => {
                let p = permute_kensler(self.index, self.count, self.perm_seed.wrapping_add(self.next_dim()));
                (p as f32 + self.jitter()) * (1.0 / self.count as f32)
            }
            // `MultijitterSampler::next_1d`.
            Seq::Multijitter => {
                let ps = self.perm_seed.wrapping_add(self.next_dim());
                let p = permute_kensler(self.index, self.count, ps.wrapping_mul(0x45fb_e943)) as f32;
                (p + self.jitter()) * (1.0 / self.count as f32)
            }
            Seq::Bose => {
                let j = self.next_dim();
                self.bose(j)
            }
            Seq::Bush => {
                let j = self.next_dim();
                self.bush(j)
            }
            // `LowDiscrepancySampler::next_1d`.
            Seq::LowDiscrepancy => {
                let ps = self.perm_seed.wrapping_add(self.next_dim());
                let i = permute_pow2(self.index, self.count, ps);
                radical_inverse_2(i, sample_tea_32(self.perm_seed, 0x48bc_48eb, 4).0)
            }
            Seq::Independent => self.rng_1d(),
        }
    }

    #[inline(never)]
    fn sequence_2d(&mut self) -> Vec2 {
        match self.seq {
            // Mitsuba `StratifiedSampler::next_2d`: one of r × r cells, jittered.
            Seq::Stratified => {
                let p = permute_kensler(self.index, self.count, self.perm_seed.wrapping_add(self.next_dim()));
                let y = p / self.res;
                let x = p - y * self.res;
                let jx = self.jitter();
                let jy = self.jitter();
                let inv = 1.0 / self.res as f32;
                Vec2::new((x as f32 + jx) * inv, (y as f32 + jy) * inv)
            }
            // `MultijitterSampler::next_2d`: a cell of the x × y grid, and within it the
            // sub-stratum that makes both 1-D projections stratified.
            Seq::Multijitter => {
                let ps = self.perm_seed.wrapping_add(self.next_dim());
                let (rx, ry) = (self.res, self.res2);
                let s = permute_kensler(self.index, self.count, ps.wrapping_mul(0x5163_3e2d));
                let y = s / rx;
                let x = s - y * rx;
                let sx = permute_kensler(x, rx, ps.wrapping_mul(0x68bc_21eb));
                let sy = permute_kensler(y, ry, ps.wrapping_mul(0x02e5_be93));
                let jx = self.jitter();
                let jy = self.jitter();
                let (inv_x, inv_y) = (1.0 / rx as f32, 1.0 / ry as f32);
                // Fused as Mitsuba's build fuses them (bit-identical results).
                Vec2::new(
                    (sy as f32 + jx).mul_add(inv_y, x as f32) * inv_x,
                    (sx as f32 + jy).mul_add(inv_x, y as f32) * inv_y,
                )
            }
            // `OrthogonalSampler::next_2d`: two `next_1d`.
            Seq::Bose | Seq::Bush => {
                let x = self.sequence_1d();
                Vec2::new(x, self.sequence_1d())
            }
            // `LowDiscrepancySampler::next_2d`: the (0, 2)-sequence (van der Corput, Sobol')
            // of the permuted index, scrambled per sequence.
            Seq::LowDiscrepancy => {
                let ps = self.perm_seed.wrapping_add(self.next_dim());
                let i = permute_pow2(self.index, self.count, ps);
                let (sx, sy) = sample_tea_32(self.perm_seed, 0x98bc_51ab, 4);
                Vec2::new(radical_inverse_2(i, sx), sobol_2(i, sy))
            }
            Seq::Independent => {
                let x = self.rng_1d();
                Vec2::new(x, self.rng_1d())
            }
        }
    }

    /// Mitsuba `OrthogonalSampler::bose`: dimension `j` of the Bose orthogonal array
    /// OA(r², r + 1, r, 2) row of the permuted sample index (columns a₀, a₁, a₀ + (j−1)·a₁
    /// mod r), stratum and sub-stratum from column j and its partner column, each permuted.
    fn bose(&mut self, j: u32) -> f32 {
        let r = self.res;
        let p = self.perm_seed;
        let i = permute_kensler(self.index % self.count, self.count, p);
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
        let jitter = self.jitter();
        (stratum as f32 + (sub as f32 + jitter) / r as f32) / r as f32
    }

    /// Mitsuba `OrthogonalSampler::bush` (strength s ≠ 2): the permuted index among r^s rows,
    /// its digits as polynomial coefficients evaluated at `j`. Mitsuba's digit extraction
    /// (`to_base_s`) puts `i·(1 − r)` (wrapping) in the constant term and shifts the base-r
    /// digits up by one; matte computes the same numbers. r^s saturates at `u32::MAX`.
    fn bush(&mut self, j: u32) -> f32 {
        let (r, s) = (self.res, self.res2);
        let p = self.perm_seed;
        let n = r.checked_pow(s).unwrap_or(u32::MAX);
        let stm = (n / r).max(1);
        let i = permute_kensler(self.index, n, p);
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
        let jitter = self.jitter();
        (stratum as f32 + (sub as f32 + jitter) / stm as f32) / r as f32
    }
}

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

/// SplitMix64 finaliser: decorrelates nearby seeds and pixel indices.
#[inline]
fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}
