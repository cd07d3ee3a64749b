//! matte's side of the renderer comparison: wall time of the render alone (scene loaded and
//! its BVH built beforehand, as Mitsuba's side times `mi.render` on a loaded scene), best of
//! several runs, with the BVH build time and traced rays.

use crate::render::accel::Backend;
use crate::render::{load, renderer};
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
    /// Best render time with everything in the CWBVH instead (the renderer before Embree),
    /// when the main run used Embree.
    pub cwbvh_seconds: Option<f64>,
}

/// Loads `job` once and renders it `repeats` times (after one warm-up render).
pub fn time_matte(job: &RenderJob, repeats: u32) -> Result<MatteTime, String> {
    let mut loaded = load::load_file(&job.scene, &job.defines).map_err(|e| e.to_string())?;
    let best_of = |loaded: &load::LoadedScene| {
        let run = || {
            let film = loaded.film.clone();
            renderer::render(&loaded.scene, &loaded.integrator, &loaded.camera, film, job.spp, 0, &|_, _| {}).1
        };
        run();
        (0..repeats.max(1)).map(|_| run()).min_by(|a, b| a.seconds.total_cmp(&b.seconds)).expect("at least one run")
    };
    let best = best_of(&loaded);
    let (backend, accel_build_seconds) = (loaded.scene.accel_backend(), loaded.scene.accel_build_seconds());
    let cwbvh_seconds = if backend == Backend::CwBvh {
        None
    } else {
        loaded.scene.set_accel_backend(Backend::CwBvh)?;
        Some(best_of(&loaded).seconds)
    };
    Ok(MatteTime {
        seconds: best.seconds,
        accel_build_seconds,
        samples: best.samples,
        rays: best.rays,
        threads: rayon::current_num_threads(),
        backend,
        cwbvh_seconds,
    })
}

/// Samples/s of `job` at each of `spp` (best of `repeats` renders each, after a warm-up):
/// constant when the per-sample cost does not depend on the sample count (no per-sample
/// allocation, no per-render cost that only amortises at high spp).
pub fn spp_scaling(job: &RenderJob, spp: &[u32], repeats: u32) -> Result<Vec<(u32, f64)>, String> {
    let loaded = load::load_file(&job.scene, &job.defines).map_err(|e| e.to_string())?;
    let run = |n: u32| {
        let s =
            renderer::render(&loaded.scene, &loaded.integrator, &loaded.camera, loaded.film.clone(), n, 0, &|_, _| {})
                .1;
        s.samples as f64 / s.seconds
    };
    run(spp[0]);
    Ok(spp.iter().map(|&n| (n, (0..repeats.max(1)).map(|_| run(n)).fold(0.0, f64::max))).collect())
}
