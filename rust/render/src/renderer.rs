//! The render loop: the film's crop window is cut into tiles rendered in parallel (rayon
//! work stealing), each by a tile driver ([`Driver`]: one path at a time by default, or many
//! in flight); each pixel has its own sampler stream, so the image depends only on the sampler and seed,
//! not on threads, tiling or the driver.
//! Every sample goes to the tile's image block, which the film accumulates (Mitsuba
//! `SamplingIntegrator::render`).

use crate::film::{Film, Image};
use crate::integrator::wavefront::StageTicks;
use crate::integrator::{Driver, Integrator, TileJob};
use crate::sampler::Sampling;
use crate::scene::Scene;
use crate::sensor::Camera;
use rayon::prelude::*;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Tile edge in pixels: small enough to balance 2–64 threads, large enough that the filter
/// border (≤ 2 px for the default Gaussian) is a small overhead.
const TILE: u32 = 16;

/// What a render measured.
#[derive(Clone, Copy, Debug, Default)]
pub struct RenderStats {
    pub samples: u64,
    pub rays: u64,
    pub seconds: f64,
    /// Samples whose radiance was NaN or infinite and was replaced by zero.
    pub invalid_samples: u64,
    /// Time per stage, all threads together ([`Driver::WavefrontProfiled`] only).
    pub stage_ticks: Option<StageTicks>,
}

/// Renders `sampling.spp` samples per pixel with `sampling`'s sampler and seed into `film`
/// (which must be fresh). `progress` is called with (tiles done, tiles total) after each tile.
pub fn render(
    scene: &Scene,
    integrator: &Integrator,
    camera: &Camera,
    film: Film,
    sampling: Sampling,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> (Image, RenderStats) {
    render_with(scene, integrator, camera, film, sampling, Driver::default(), progress)
}

/// [`render`] with the tile driver `driver` (the image is the same estimator with either:
/// each pixel's samples draw the same numbers).
pub fn render_with(
    scene: &Scene,
    integrator: &Integrator,
    camera: &Camera,
    film: Film,
    sampling: Sampling,
    driver: Driver,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> (Image, RenderStats) {
    let start = Instant::now();
    if let Integrator::ParticleTracer(pt) = integrator {
        crate::accel::take_ray_count();
        let (image, invalid_samples) = pt.render(scene, camera, &film, sampling);
        let stats = RenderStats {
            samples: film.width() as u64 * film.height() as u64 * sampling.spp as u64,
            rays: 0,
            seconds: start.elapsed().as_secs_f64(),
            invalid_samples,
            stage_ticks: None,
        };
        return (image, stats);
    }
    let tiles = film.tiles(TILE);
    let total = tiles.len() as u64;
    let done = AtomicU64::new(0);
    let invalid = AtomicU64::new(0);
    let rays = AtomicU64::new(0);
    let job = TileJob { scene, camera, sampling, width: film.width() as u64 };
    let film = Mutex::new(film);
    let stage_ticks = Mutex::new(StageTicks::default());
    tiles.par_iter().for_each(|tile| {
        let mut block = film.lock().expect("film lock").new_block(tile);
        crate::accel::take_ray_count();
        let mut ticks = StageTicks::default();
        let bad = integrator.render_tile(driver, &job, &mut block, &mut ticks);
        if driver == Driver::WavefrontProfiled {
            stage_ticks.lock().expect("profile lock").add(&ticks);
        }
        rays.fetch_add(crate::accel::take_ray_count(), Ordering::Relaxed);
        invalid.fetch_add(bad, Ordering::Relaxed);
        film.lock().expect("film lock").put_block(&block);
        progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
    });
    let film = film.into_inner().expect("film lock");
    let crop = film.crop();
    let stats = RenderStats {
        samples: crop.size[0] as u64 * crop.size[1] as u64 * sampling.spp as u64,
        rays: rays.into_inner(),
        seconds: start.elapsed().as_secs_f64(),
        invalid_samples: invalid.into_inner(),
        stage_ticks: (driver == Driver::WavefrontProfiled).then(|| stage_ticks.into_inner().expect("profile lock")),
    };
    (film.develop(), stats)
}
