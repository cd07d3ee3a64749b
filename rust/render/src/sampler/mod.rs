//! Mitsuba 3.9.1's samplers (`src/samplers/*.cpp`, docs/renderer-semantics.md §5), one file
//! each: `independent.rs`, `stratified.rs`, `multijitter.rs`, `orthogonal.rs`, `ldsampler.rs`.
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
//! What they share: `stream.rs` (the state a pixel's sequence draws from) and `random.rs`
//! (Mitsuba's hashes and permutations). [`Sampling`] reads the sampler plugins' properties
//! ([`FromProps`]); [`Sampler`] draws.

mod independent;
mod ldsampler;
mod multijitter;
mod orthogonal;
mod random;
mod stratified;
mod stream;

pub use ldsampler::{radical_inverse_2, sobol_2};
pub use random::{permute_kensler, permute_pow2, sample_tea_32};

use crate::load::props::{FromProps, PluginProps};
use glam::Vec2;
use ldsampler::LowDiscrepancy;
use matte_brdf::rng::Pcg32;
use matte_scene_file::SceneError;
use multijitter::Multijitter;
use orthogonal::Orthogonal;
use random::splitmix64;
use stratified::Stratified;
use stream::Stream;

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
        match self {
            SamplerKind::Independent => spp,
            SamplerKind::Stratified { .. } => stratified::count(spp),
            SamplerKind::Multijitter { .. } => multijitter::count(spp),
            SamplerKind::Orthogonal { .. } => orthogonal::count(spp),
            SamplerKind::LowDiscrepancy => ldsampler::count(spp),
        }
    }
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
#[derive(Clone, Copy, Debug)]
enum Seq {
    Independent,
    Stratified(Stratified),
    Multijitter(Multijitter),
    Orthogonal(Orthogonal),
    LowDiscrepancy(LowDiscrepancy),
}

/// A per-pixel sample stream: a [`Pcg32`], plus for the stratified samplers the sample and
/// dimension index within the pixel's sequence. The drivers call [`Sampler::advance`] after
/// each sample.
#[derive(Clone, Debug)]
pub struct Sampler {
    st: Stream,
    seq: Seq,
}

/// Dr.Jit's `PCG32_DEFAULT_STREAM`.
const PCG32_DEFAULT_STREAM: u64 = 0xda3e_39cb_94b9_5bdb;

impl Sampler {
    /// The `independent` stream for one pixel: `seed` picks the sequence family, `pixel` the
    /// stream.
    pub fn for_pixel(seed: u64, pixel: u64) -> Self {
        Sampler { st: Stream::new(independent::pixel_rng(seed, pixel), true, 0), seq: Seq::Independent }
    }

    /// Exactly Mitsuba's scalar-variant sampler `kind` with `sample_count` (rounded as
    /// Mitsuba rounds it) and `seed` property `base_seed`, after `sampler.seed(seed)`: PCG32
    /// seeded with (base_seed + seed, the default stream) (`PCG32Sampler::seed`,
    /// `src/render/sampler.cpp`), permutation seed `sample_tea_32(base_seed, seed).0`
    /// (`compute_per_sequence_seed` with one sequence per wavefront).
    pub fn mitsuba(kind: SamplerKind, sample_count: u32, base_seed: u32, seed: u32) -> Self {
        let n = sample_count;
        let (seq, jitter) = match kind {
            SamplerKind::Independent => (Seq::Independent, true),
            SamplerKind::Stratified { jitter } => (Seq::Stratified(Stratified::new(n)), jitter),
            SamplerKind::Multijitter { jitter } => (Seq::Multijitter(Multijitter::new(n)), jitter),
            SamplerKind::Orthogonal { jitter, strength } => (Seq::Orthogonal(Orthogonal::new(n, strength)), jitter),
            SamplerKind::LowDiscrepancy => (Seq::LowDiscrepancy(LowDiscrepancy::new(n)), false),
        };
        let rng = Pcg32::new(base_seed.wrapping_add(seed) as u64, PCG32_DEFAULT_STREAM);
        let perm_seed = sample_tea_32(base_seed, seed, 4).0;
        Sampler { st: Stream::new(rng, jitter, perm_seed), seq }
    }

    /// The next 32 random bits of the stream's generator.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        self.st.rng.next_u32()
    }

    /// The next dimension of the current sample, in [0, 1).
    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        if let Seq::Independent = self.seq {
            return self.st.rng_1d();
        }
        self.sequence_1d()
    }

    /// The next two-dimensional dimension of the current sample, in [0, 1)².
    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        if let Seq::Independent = self.seq {
            let x = self.st.rng_1d();
            return Vec2::new(x, self.st.rng_1d());
        }
        self.sequence_2d()
    }

    /// Ends the current sample: the next draw is dimension 0 of the next sample (Mitsuba
    /// `Sampler::advance`). The independent stream simply continues.
    #[inline]
    pub fn advance(&mut self) {
        self.st.index = self.st.index.wrapping_add(1);
        self.st.dim = 0;
    }

    #[inline(never)]
    fn sequence_1d(&mut self) -> f32 {
        let st = &mut self.st;
        match self.seq {
            Seq::Stratified(s) => s.next_1d(st),
            Seq::Multijitter(s) => s.next_1d(st),
            Seq::Orthogonal(s) => s.next_1d(st),
            Seq::LowDiscrepancy(s) => s.next_1d(st),
            Seq::Independent => st.rng_1d(),
        }
    }

    #[inline(never)]
    fn sequence_2d(&mut self) -> Vec2 {
        let st = &mut self.st;
        match self.seq {
            Seq::Stratified(s) => s.next_2d(st),
            Seq::Multijitter(s) => s.next_2d(st),
            Seq::Orthogonal(s) => s.next_2d(st),
            Seq::LowDiscrepancy(s) => s.next_2d(st),
            Seq::Independent => {
                let x = st.rng_1d();
                Vec2::new(x, st.rng_1d())
            }
        }
    }
}
