//! The two sides of a validation run: K independent passes of the Rust renderer (in
//! process) and of Mitsuba (`python -m matte_mitsuba.passes` in the Python environment matte
//! is installed in, [`crate::installation`], which only renders and writes each pass image). Everything computed from the
//! passes (moments, region means, the spp budget) is computed here, once, for both sides.

use super::crop::pixel_box;
use super::stats::Moments;
use crate::installation::PythonSide;
use glam::DVec3;
use matte_render::film::{Image, SplatWeights};
use matte_render::image_io;
use matte_render::load;
use matte_render::renderer;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::Stdio;
use std::time::Instant;

/// The renderer of one side: the Rust renderer (in validation's reference role: itself with
/// other seeds, a size check of the test), or Mitsuba in a variant.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Renderer {
    Matte,
    /// Mitsuba 3.9.1 in this variant (`scalar_rgb`, `llvm_ad_rgb`, …).
    Mitsuba(String),
}

/// Samples per pixel of each pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Budget {
    PerPass(u32),
    /// `factor × the scene's sample_count` in total, split over the passes; each renderer
    /// reads the sample_count from the scene it loads anyway.
    SceneMultiple(u32),
}

impl Budget {
    pub fn per_pass(self, scene_spp: u32, passes: u32) -> u32 {
        match self {
            Budget::PerPass(n) => n.max(1),
            Budget::SceneMultiple(f) => (f * scene_spp / passes.max(1)).max(1),
        }
    }
}

/// How one side renders.
#[derive(Clone, Debug)]
pub struct PassPlan {
    pub passes: u32,
    pub spp: Budget,
    /// Seed of pass k is `seed + k`.
    pub seed: u64,
    /// `-D` parameters for this side.
    pub defines: Vec<(String, String)>,
    /// Image regions `[x0, y0, x1, y1]` (fractions of width and height, rounded to pixels by
    /// [`super::crop::pixel_box`]) whose mean is recorded per pass.
    pub regions: Vec<[f64; 4]>,
}

/// Mean RGB of `img` over the region `r` (fractions, rounded by [`pixel_box`]).
pub fn region_mean(img: &Image, r: [f64; 4]) -> DVec3 {
    let b = pixel_box(img.width, img.height, r);
    let mut sum = DVec3::ZERO;
    for y in b.y0..b.y1 {
        for x in b.x0..b.x1 {
            sum += img.get(x, y).as_dvec3();
        }
    }
    sum / b.area() as f64
}

/// The pass images, their moments and what they cost.
pub struct Side {
    /// The K pass images, in seed order.
    pub images: Vec<Image>,
    pub moments: Moments,
    pub seconds: f64,
    pub spp: u32,
    pub label: String,
    /// Per region of the plan, the region's mean in each pass.
    pub region_pass_means: Vec<Vec<DVec3>>,
}

/// Builds a side from its pass images: moments and region means.
pub fn side_from_images(
    images: Vec<Image>,
    regions: &[[f64; 4]],
    seconds: f64,
    spp: u32,
    label: String,
) -> Result<Side, String> {
    let first = images.first().ok_or("no passes")?;
    let mut moments = Moments::new(first.width, first.height);
    for img in &images {
        moments.add(img)?;
    }
    let region_pass_means = regions.iter().map(|r| images.iter().map(|img| region_mean(img, *r)).collect()).collect();
    Ok(Side { images, moments, seconds, spp, label, region_pass_means })
}

/// Samples per pixel of each pass of `scene` under `plan` (the scene's `sample_count` is
/// read only when the budget is a multiple of it).
pub fn spp_per_pass(scene: &Path, plan: &PassPlan) -> Result<u32, String> {
    match plan.spp {
        Budget::PerPass(n) => Ok(n.max(1)),
        Budget::SceneMultiple(_) => {
            let loaded = load::load_file(scene, &plan.defines).map_err(|e| e.to_string())?;
            Ok(loaded.sampling.with_spp(plan.spp.per_pass(loaded.sampling.spp, plan.passes)).spp)
        }
    }
}

/// K passes of the Rust renderer, its film weighting samples by `splat` (that of the Mitsuba
/// variant it is compared with: [`SplatWeights::of_mitsuba_variant`]). `progress(k)` after
/// each pass.
pub fn rust_side(scene: &Path, plan: &PassPlan, splat: SplatWeights, progress: &dyn Fn(u32)) -> Result<Side, String> {
    let mut seconds = 0.0;
    // Loaded once (meshes, BVH, BSDF tables); each pass renders into a copy of the fresh film.
    let loaded = load::load_file(scene, &plan.defines).map_err(|e| e.to_string())?;
    // Rounded as the scene's sampler rounds it, as Mitsuba's `render(spp=…)` rounds the spp
    // it is given: both sides render the same number of samples.
    let sampling = loaded.sampling.with_spp(plan.spp.per_pass(loaded.sampling.spp, plan.passes));
    let spp_used = sampling.spp;
    let mut images = Vec::with_capacity(plan.passes as usize);
    for k in 0..plan.passes {
        let t = Instant::now();
        let (img, stats) = renderer::render(
            &loaded.scene,
            &loaded.integrator,
            &loaded.camera,
            loaded.film.clone().with_splat_weights(splat),
            sampling.with_seed(plan.seed + k as u64),
            &|_, _| {},
        );
        seconds += t.elapsed().as_secs_f64();
        if stats.invalid_samples > 0 {
            eprintln!("matte: warning: {} non-finite samples set to zero in pass {k}", stats.invalid_samples);
        }
        images.push(img);
        progress(k + 1);
    }
    side_from_images(images, &plan.regions, seconds, spp_used, "matte".into())
}

/// K passes of Mitsuba in `variant`, run by `matte_mitsuba.passes` in `python` (one with
/// Mitsuba, [`crate::installation::mitsuba_side`]); `work` receives its files.
pub fn mitsuba_side(
    python: &PythonSide,
    scene: &Path,
    variant: &str,
    plan: &PassPlan,
    work: &Path,
    progress: &dyn Fn(u32),
) -> Result<Side, String> {
    let spp = spp_per_pass(scene, plan)?;
    let mut cmd = python.module("passes");
    cmd.arg(scene).arg("--out").arg(work).arg("--variant").arg(variant);
    cmd.arg("--passes").arg(plan.passes.to_string()).arg("--seed").arg(plan.seed.to_string());
    cmd.arg("--spp").arg(spp.to_string());
    for (k, v) in &plan.defines {
        cmd.arg("-D").arg(format!("{k}={v}"));
    }
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start {}: {e}", python.python.display()))?;
    if let Some(out) = child.stdout.take() {
        for line in BufReader::new(out).lines().map_while(Result::ok) {
            if let Some(rest) = line.strip_prefix("pass ")
                && let Some((k, _)) = rest.split_once('/')
                && let Ok(k) = k.parse()
            {
                progress(k);
            }
        }
    }
    let output = child.wait_with_output().map_err(|e| e.to_string())?;
    if !output.status.success() {
        let err = String::from_utf8_lossy(&output.stderr);
        let line = err.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("failed without a message");
        return Err(format!("Mitsuba ({variant}): {line}"));
    }
    let images = (0..plan.passes)
        .map(|k| image_io::read_exr(&work.join(pass_file_name(k))))
        .collect::<Result<Vec<_>, String>>()?;
    let info_path = work.join("passes.json");
    let info: DriverInfo = serde_json::from_str(
        &std::fs::read_to_string(&info_path).map_err(|e| format!("{}: {e}", info_path.display()))?,
    )
    .map_err(|e| format!("{}: {e}", info_path.display()))?;
    side_from_images(images, &plan.regions, info.render_seconds, spp, format!("mitsuba {variant}"))
}

/// What the Mitsuba driver reports about its run in `passes.json` (it writes the variant,
/// passes, spp, seed and load time too; only the render time is used here).
#[derive(serde::Deserialize)]
struct DriverInfo {
    /// Seconds spent rendering all passes.
    render_seconds: f64,
}

/// The file the Mitsuba driver writes pass `k` to (`matte_mitsuba.passes`).
pub fn pass_file_name(k: u32) -> String {
    format!("pass_{k:04}.exr")
}

/// [`mitsuba_side`] with the installation's Python side; `work` is removed afterwards.
pub fn mitsuba_side_installed(
    scene: &Path,
    variant: &str,
    plan: &PassPlan,
    work: &Path,
    progress: &dyn Fn(u32),
) -> Result<Side, String> {
    let side = mitsuba_side(&crate::installation::mitsuba_side()?, scene, variant, plan, work, progress);
    let _ = std::fs::remove_dir_all(work);
    side
}
