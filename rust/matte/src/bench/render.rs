//! matte's side of the renderer comparison: wall time of the render alone (scene loaded and
//! its BVH built beforehand, as Mitsuba's side times `mi.render` on a loaded scene), best of
//! several runs, with the BVH build time and traced rays; and the render time of each
//! diffuse model against Lambert's on the same scene.

use matte_render::accel::Backend;
use matte_render::integrator::Driver;
use matte_render::{load, renderer};
use std::path::PathBuf;

/// One scene as both renderers see it: the file, its `-D` parameters and the spp.
#[derive(Clone, Debug)]
pub struct RenderJob {
    pub name: String,
    pub scene: PathBuf,
    pub defines: Vec<(String, String)>,
    pub spp: u32,
}

#[derive(Clone, Debug)]
pub struct MatteTime {
    /// Best render wall time over the repeats.
    pub seconds: f64,
    pub accel_build_seconds: f64,
    pub samples: u64,
    pub rays: u64,
    pub threads: usize,
    /// The structure that traced the meshes.
    pub backend: Backend,
    /// Best render time with the other tile driver: [`Driver::Wavefront`] when the default is
    /// [`Driver::OnePath`], and the reverse.
    pub other_driver_seconds: f64,
    /// Share of each stage of the default arrangement's render, in the order of
    /// [`StageTicks::NAMES`](matte_render::integrator::wavefront::StageTicks::NAMES) (`None`
    /// for integrators the wavefront does not drive).
    pub stage_fractions: Option<[f64; 5]>,
    /// Best render time with everything in the CWBVH instead (the renderer before Embree),
    /// when the main run used Embree.
    pub cwbvh_seconds: Option<f64>,
}

/// Loads `job` once and times its render in three arrangements taking turns, each `repeats`
/// times after one warm-up render (so that the machine's load hits them alike): the default
/// (the default tile driver, Embree), the other tile driver, and everything in the CWBVH (the
/// ray queries before Embree); then renders it once more with the wavefront's stages counted
/// ([`Driver::WavefrontProfiled`], not timed).
pub fn time_matte(job: &RenderJob, repeats: u32) -> Result<MatteTime, String> {
    let mut loaded = load::load_file(&job.scene, &job.defines).map_err(|e| e.to_string())?;
    let backend = loaded.scene.accel_backend();
    let mut configs = vec![(backend, Driver::default()), (backend, other_driver())];
    if backend != Backend::CwBvh {
        configs.push((Backend::CwBvh, Driver::default()));
    }
    let mut best: Vec<Option<renderer::RenderStats>> = vec![None; configs.len()];
    let mut accel_build_seconds = loaded.scene.accel_build_seconds();
    for round in 0..=repeats.max(1) {
        for (k, &(b, driver)) in configs.iter().enumerate() {
            if loaded.scene.accel_backend() != b {
                loaded.scene.set_accel_backend(b)?;
            }
            if b == backend {
                accel_build_seconds = loaded.scene.accel_build_seconds();
            }
            let film = loaded.film.clone();
            let stats = renderer::render_with(
                &loaded.scene,
                &loaded.integrator,
                &loaded.camera,
                film,
                loaded.sampling.with_spp(job.spp).with_seed(0),
                driver,
                &|_, _| {},
            )
            .1;
            // Round 0 warms up (caches, page faults, thread pool).
            if round > 0 && best[k].is_none_or(|s| stats.seconds < s.seconds) {
                best[k] = Some(stats);
            }
        }
    }
    let best: Vec<renderer::RenderStats> = best.into_iter().map(|s| s.expect("at least one timed round")).collect();
    // Where the default arrangement's time goes: one more render, counting each stage.
    if loaded.scene.accel_backend() != backend {
        loaded.scene.set_accel_backend(backend)?;
    }
    let profiled = renderer::render_with(
        &loaded.scene,
        &loaded.integrator,
        &loaded.camera,
        loaded.film.clone(),
        loaded.sampling.with_spp(job.spp).with_seed(0),
        Driver::WavefrontProfiled,
        &|_, _| {},
    )
    .1;
    Ok(MatteTime {
        seconds: best[0].seconds,
        accel_build_seconds,
        samples: best[0].samples,
        rays: best[0].rays,
        threads: rayon::current_num_threads(),
        backend,
        other_driver_seconds: best[1].seconds,
        stage_fractions: profiled.stage_ticks.map(|t| t.fractions()),
        cwbvh_seconds: best.get(2).map(|s| s.seconds),
    })
}

/// The tile driver that is not the default (timed beside it).
pub fn other_driver() -> Driver {
    if Driver::default() == Driver::OnePath { Driver::Wavefront } else { Driver::OnePath }
}

/// The diffuse models whose render time `matte bench` compares with Lambert's: every registered
/// one that builds from its defaults (Lambert first; not `tabulated_brdf`, which needs a table).
pub fn models() -> Vec<&'static str> {
    matte_brdf::default_models().collect()
}

/// Render time of the study's room (`scenes/study/room.xml`) with every diffuse surface as each of [`models`] (its
/// `$bsdf` parameter; the model's default parameters), at `res`² and `spp`, the models taking
/// turns, best of `repeats` after a warm-up round. Returns `(model, seconds)`.
pub fn time_models(scenes: &std::path::Path, res: u32, spp: u32, repeats: u32) -> Result<Vec<(String, f64)>, String> {
    let file = scenes.join("study/room.xml");
    let models = models();
    let scenes = models
        .iter()
        .map(|m| {
            let defines = vec![("res".to_string(), res.to_string()), ("bsdf".to_string(), m.to_string())];
            load::load_file(&file, &defines).map_err(|e| e.to_string())
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut best = vec![f64::INFINITY; models.len()];
    for round in 0..=repeats.max(1) {
        for (k, loaded) in scenes.iter().enumerate() {
            let film = loaded.film.clone();
            let sampling = loaded.sampling.with_spp(spp).with_seed(0);
            let s = renderer::render(&loaded.scene, &loaded.integrator, &loaded.camera, film, sampling, &|_, _| {}).1;
            if round > 0 {
                best[k] = best[k].min(s.seconds);
            }
        }
    }
    Ok(models.iter().map(|m| m.to_string()).zip(best).collect())
}

/// Samples/s of `job` at each of `spp` (best of `repeats` renders each, after a warm-up):
/// constant when the per-sample cost does not depend on the sample count (no per-sample
/// allocation, no per-render cost that only amortises at high spp).
pub fn spp_scaling(job: &RenderJob, spp: &[u32], repeats: u32) -> Result<Vec<(u32, f64)>, String> {
    let loaded = load::load_file(&job.scene, &job.defines).map_err(|e| e.to_string())?;
    let run = |n: u32| {
        let sampling = loaded.sampling.with_spp(n).with_seed(0);
        let film = loaded.film.clone();
        let s = renderer::render(&loaded.scene, &loaded.integrator, &loaded.camera, film, sampling, &|_, _| {}).1;
        s.samples as f64 / s.seconds
    };
    run(spp[0]);
    Ok(spp.iter().map(|&n| (n, (0..repeats.max(1)).map(|_| run(n)).fold(0.0, f64::max))).collect())
}
