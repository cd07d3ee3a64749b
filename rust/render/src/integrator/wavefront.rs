//! Many paths in flight per thread: a tile driver for the `path` and `direct` integrators
//! ([`super::Driver::Wavefront`]; docs/performance.md).
//!
//! Each of the [`LANES`] lanes renders whole pixels of a tile, one after the other, every
//! sample of a pixel in turn with the pixel's own sampler stream: the numbers drawn, and so
//! each sample's radiance, are exactly those of the one-path driver ([`super::Integrator::li`]);
//! only the order in which samples reach the image block changes
//! (`tests/render/render_drivers.rs`).
//! Every step traces the lanes' pending rays eight at a time
//! ([`Scene::intersect8`](crate::scene::Scene::intersect8): Embree's `rtcIntersect8`),
//! advances each lane's state machine with its hit, and tests all the shadow rays those
//! advances asked for eight at a time
//! ([`Scene::occluded8`](crate::scene::Scene::occluded8)). A lane whose sample ends
//! splats it and starts its next sample (or its next pixel) at once, so the
//! lanes stay full until the tile runs out of pixels.

use super::sample_integrator::{SampleIntegrator, ShadowTest, TileJob};
use crate::film::{ImageBlock, Tile};
use crate::geometry::Ray;
use crate::sampler::{Sampler, Sampling};
use glam::{Vec2, Vec3};

/// Paths in flight per thread. Each step runs Embree's packet traversal, then every lane's
/// shading, then the packet occlusion test: code that together overflows the 32 KB L1
/// instruction cache, so the step's cost depends on how many lanes share it. Measured with
/// callgrind's cache and branch simulation (docs/performance.md): with 8 lanes, 9× the L1i misses
/// of one path per thread and no gain; with 32, 2.4× and 8–9 % fewer estimated cycles on the
/// room and the bunny, +2 % on the Cornell box.
pub const LANES: usize = 32;

/// Rays per batched query (Embree's `rtcIntersect8`/`rtcOccluded8`).
const PACKET: usize = 8;

/// One lane: the pixel it renders, its sampler and the sample in flight.
struct Lane<S> {
    sampler: Sampler,
    /// The pixel's corner on the film.
    pixel: Vec2,
    /// Film position of the sample in flight.
    pos: Vec2,
    /// Samples of the pixel not started yet.
    samples_left: u32,
    /// The sample's integrator state.
    state: S,
    /// The ray whose hit the state waits for.
    ray: Ray,
}

/// The pixels of a tile in row-major order, handed out to lanes as they free up.
struct PixelQueue {
    tile: Tile,
    next: u32,
    width: u64,
    sampling: Sampling,
}

impl PixelQueue {
    fn pop(&mut self) -> Option<(Vec2, Sampler)> {
        let [w, h] = self.tile.size;
        if self.next >= w * h {
            return None;
        }
        let (px, py) = (self.tile.offset[0] + self.next % w, self.tile.offset[1] + self.next / w);
        self.next += 1;
        let sampler = self.sampling.sampler(py as u64 * self.width + px as u64);
        Some((Vec2::new(px as f32, py as f32), sampler))
    }
}

/// Where a thread's time went in the wavefront's steps, in timestamp-counter ticks (`rdtsc`),
/// counted only with `PROFILE` ([`super::Driver::WavefrontProfiled`], `matte bench`'s profile
/// split). Light sampling, BSDF evaluation and sampling and the path logic are all in
/// `shading` (the integrators' `advance`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StageTicks {
    /// Closest-hit queries, with the packing into Embree's packets.
    pub trace: u64,
    /// Surface interactions built from the hits.
    pub hit_points: u64,
    /// The integrators' `advance`.
    pub shading: u64,
    /// Shadow-ray queries and adding the unblocked contributions.
    pub shadow_rays: u64,
    /// Splatting finished samples, camera rays and sampler streams of the next samples.
    pub film: u64,
}

impl StageTicks {
    pub const NAMES: [&'static str; 5] = ["trace", "hit points", "shading", "shadow rays", "film & camera"];

    pub fn add(&mut self, o: &StageTicks) {
        self.trace += o.trace;
        self.hit_points += o.hit_points;
        self.shading += o.shading;
        self.shadow_rays += o.shadow_rays;
        self.film += o.film;
    }

    /// Each stage's share of the total, in the order of [`Self::NAMES`].
    pub fn fractions(&self) -> [f64; 5] {
        let v = [self.trace, self.hit_points, self.shading, self.shadow_rays, self.film];
        let total = v.iter().sum::<u64>().max(1) as f64;
        v.map(|x| x as f64 / total)
    }
}

/// The timestamp counter (x86-64), or nanoseconds since the first call elsewhere.
#[inline(always)]
fn ticks() -> u64 {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: `rdtsc` has no preconditions on x86-64.
        unsafe { core::arch::x86_64::_rdtsc() }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        static EPOCH: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
        EPOCH.get_or_init(std::time::Instant::now).elapsed().as_nanos() as u64
    }
}

/// Renders `job.sampling.spp` samples of every pixel of `block`'s tile into `block`. Returns how many
/// samples were not finite (splatted as zero). With `PROFILE`, adds each stage's ticks to
/// `profile`.
pub fn render_tile<I: SampleIntegrator, const PROFILE: bool>(
    integrator: &I,
    job: &TileJob,
    block: &mut ImageBlock,
    profile: &mut StageTicks,
) -> u64 {
    let scene = job.scene;
    let clock = || if PROFILE { ticks() } else { 0 };
    let mut pixels = PixelQueue { tile: block.tile(), next: 0, width: job.width, sampling: job.sampling };
    let mut bad = 0u64;
    let placeholder = Ray::new(Vec3::ZERO, Vec3::Z, 0.0);
    let mut live: [Option<Lane<I::State>>; LANES] =
        std::array::from_fn(|_| next_sample(integrator, job, &mut pixels, None, block, &mut bad));
    let mut shadows: Vec<ShadowTest> = Vec::with_capacity(4 * LANES);
    let mut shadow_owner: Vec<usize> = Vec::with_capacity(4 * LANES);
    while live.iter().any(Option::is_some) {
        let t0 = clock();
        let mut hits = [None; LANES];
        for (c, chunk) in live.chunks(PACKET).enumerate() {
            let rays: [Ray; PACKET] = std::array::from_fn(|k| chunk[k].as_ref().map_or(placeholder, |l| l.ray));
            let active: [bool; PACKET] = std::array::from_fn(|k| chunk[k].is_some());
            if active.iter().any(|&a| a) {
                hits[c * PACKET..(c + 1) * PACKET].copy_from_slice(&scene.intersect8(&rays, active));
            }
        }
        shadows.clear();
        shadow_owner.clear();
        let mut next: [Option<Ray>; LANES] = [None; LANES];
        let mut t = clock();
        if PROFILE {
            profile.trace += t - t0;
        }
        for i in 0..LANES {
            let Some(lane) = live[i].as_mut() else { continue };
            let si = hits[i].map(|hit| scene.interaction(&lane.ray, hit));
            let t_hit = clock();
            next[i] = integrator.advance(scene, &mut lane.sampler, &mut lane.state, si, &mut shadows);
            shadow_owner.resize(shadows.len(), i);
            if PROFILE {
                let t_end = ticks();
                profile.hit_points += t_hit - t;
                profile.shading += t_end - t_hit;
                t = t_end;
            }
        }
        for (tests, owners) in shadows.chunks(PACKET).zip(shadow_owner.chunks(PACKET)) {
            let rays: [Ray; PACKET] = std::array::from_fn(|k| tests.get(k).map_or(placeholder, |t| t.ray));
            let active: [bool; PACKET] = std::array::from_fn(|k| k < tests.len());
            let blocked = scene.occluded8(&rays, active);
            for (k, test) in tests.iter().enumerate() {
                if !blocked[k] {
                    let lane = live[owners[k]].as_mut().expect("shadow rays belong to live lanes");
                    *I::radiance(&mut lane.state) += test.contribution;
                }
            }
        }
        let t_film = clock();
        for i in 0..LANES {
            let Some(lane) = live[i].as_mut() else { continue };
            match next[i] {
                Some(ray) => lane.ray = ray,
                None => live[i] = next_sample(integrator, job, &mut pixels, live[i].take(), block, &mut bad),
            }
        }
        if PROFILE {
            profile.shadow_rays += t_film - t;
            profile.film += ticks() - t_film;
        }
    }
    bad
}

/// Splats the finished sample of `done` (if any) and starts the lane's next sample: the
/// pixel's next one, or the first of the queue's next pixel. `None` when the tile is done.
/// Samples whose radiance is zero without tracing are splatted here directly.
#[inline]
fn next_sample<I: SampleIntegrator>(
    integrator: &I,
    job: &TileJob,
    pixels: &mut PixelQueue,
    done: Option<Lane<I::State>>,
    block: &mut ImageBlock,
    bad: &mut u64,
) -> Option<Lane<I::State>> {
    let (mut pixel, mut sampler, mut samples_left) = match done {
        Some(mut lane) => {
            let mut l = *I::radiance(&mut lane.state);
            if !l.is_finite() {
                l = Vec3::ZERO;
                *bad += 1;
            }
            block.put(lane.pos, l);
            lane.sampler.advance();
            (lane.pixel, lane.sampler, lane.samples_left)
        }
        None => {
            let (pixel, sampler) = pixels.pop()?;
            (pixel, sampler, job.sampling.spp)
        }
    };
    loop {
        if samples_left == 0 {
            (pixel, sampler) = pixels.pop()?;
            samples_left = job.sampling.spp;
        }
        samples_left -= 1;
        let pos = pixel + sampler.next_2d();
        let camera_ray = job.camera.sample_ray(pos, &mut sampler);
        match integrator.start(camera_ray) {
            Some((state, ray)) => return Some(Lane { sampler, pixel, pos, samples_left, state, ray }),
            None => {
                block.put(pos, Vec3::ZERO);
                sampler.advance();
            }
        }
    }
}
