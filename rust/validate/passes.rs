//! The two sides of a validation run: K independent passes of the Rust renderer (in
//! process) and of Mitsuba 3.9.1 (through `validation/mitsuba_passes.py` in the project's
//! `.venv`), each reduced to per-pixel moments.

use super::stats::Moments;
use crate::render::image_io;
use crate::render::load;
use crate::render::renderer;
use glam::DVec3;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

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
    /// Image regions `[x0, y0, x1, y1]` (fractions of width and height) whose mean is
    /// recorded per pass.
    pub regions: Vec<[f32; 4]>,
}

/// Mean RGB of `img` over the region `r` (fractions; at least one pixel).
pub fn region_mean(img: &crate::render::film::Image, r: [f32; 4]) -> DVec3 {
    let (w, h) = (img.width as f32, img.height as f32);
    let x0 = ((r[0] * w) as u32).min(img.width - 1);
    let y0 = ((r[1] * h) as u32).min(img.height - 1);
    let x1 = ((r[2] * w).ceil() as u32).clamp(x0 + 1, img.width);
    let y1 = ((r[3] * h).ceil() as u32).clamp(y0 + 1, img.height);
    let mut sum = DVec3::ZERO;
    for y in y0..y1 {
        for x in x0..x1 {
            sum += img.pixels[(y * img.width + x) as usize].as_dvec3();
        }
    }
    sum / ((x1 - x0) * (y1 - y0)) as f64
}

/// Moments plus what it cost.
pub struct Side {
    pub moments: Moments,
    pub seconds: f64,
    pub spp: u32,
    pub label: String,
    /// Per region of the plan, the region's mean in each pass.
    pub region_pass_means: Vec<Vec<DVec3>>,
}

/// K passes of the Rust renderer. `progress(k)` after each pass.
pub fn rust_side(scene: &Path, plan: &PassPlan, progress: &dyn Fn(u32)) -> Result<Side, String> {
    let mut moments: Option<Moments> = None;
    let mut seconds = 0.0;
    // Loaded once (meshes, BVH, BSDF tables); each pass renders into a copy of the fresh film.
    let loaded = load::load_file(scene, &plan.defines).map_err(|e| e.to_string())?;
    let spp_used = plan.spp.per_pass(loaded.spp, plan.passes);
    let mut region_pass_means = vec![Vec::new(); plan.regions.len()];
    for k in 0..plan.passes {
        let t = Instant::now();
        let (img, stats) = renderer::render(
            &loaded.scene,
            &loaded.integrator,
            &loaded.camera,
            loaded.film.clone(),
            spp_used,
            plan.seed + k as u64,
            &|_, _| {},
        );
        seconds += t.elapsed().as_secs_f64();
        if stats.invalid_samples > 0 {
            eprintln!("matte: warning: {} non-finite samples set to zero in pass {k}", stats.invalid_samples);
        }
        for (acc, r) in region_pass_means.iter_mut().zip(&plan.regions) {
            acc.push(region_mean(&img, *r));
        }
        let m = moments.get_or_insert_with(|| Moments::new(img.width, img.height));
        m.add(&img)?;
        progress(k + 1);
    }
    Ok(Side { moments: moments.ok_or("no passes")?, seconds, spp: spp_used, label: "matte".into(), region_pass_means })
}

/// K passes of Mitsuba in `variant`, run by the Python driver; `work` receives its files.
pub fn mitsuba_side(
    python: &Path,
    driver: &Path,
    scene: &Path,
    variant: &str,
    plan: &PassPlan,
    work: &Path,
    progress: &dyn Fn(u32),
) -> Result<Side, String> {
    let mut cmd = Command::new(python);
    cmd.arg(driver).arg(scene).arg("--out").arg(work).arg("--variant").arg(variant);
    cmd.arg("--passes").arg(plan.passes.to_string()).arg("--seed").arg(plan.seed.to_string());
    match plan.spp {
        Budget::PerPass(n) => cmd.arg("--spp").arg(n.to_string()),
        Budget::SceneMultiple(f) => cmd.arg("--scene-multiple").arg(f.to_string()),
    };
    for (k, v) in &plan.defines {
        cmd.arg("-D").arg(format!("{k}={v}"));
    }
    for r in &plan.regions {
        cmd.arg("--region").arg(format!("{},{},{},{}", r[0], r[1], r[2], r[3]));
    }
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start {} (run `make venv` first): {e}", python.display()))?;
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
    let mean = image_io::read_exr(&work.join("mean.exr"))?;
    let var = image_io::read_exr(&work.join("var.exr"))?;
    let info: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(work.join("passes.json")).map_err(|e| e.to_string())?)
            .map_err(|e| e.to_string())?;
    let pass_means = info["pass_means"]
        .as_array()
        .ok_or("passes.json: no pass_means")?
        .iter()
        .map(|v| {
            let c = |i: usize| v[i].as_f64().unwrap_or(f64::NAN);
            DVec3::new(c(0), c(1), c(2))
        })
        .collect();
    let moments = Moments::from_mean_var(&mean, &var, plan.passes, pass_means)?;
    let triple = |v: &serde_json::Value| {
        DVec3::new(
            v[0].as_f64().unwrap_or(f64::NAN),
            v[1].as_f64().unwrap_or(f64::NAN),
            v[2].as_f64().unwrap_or(f64::NAN),
        )
    };
    let region_pass_means = info["region_pass_means"]
        .as_array()
        .map(|rs| {
            rs.iter().map(|r| r.as_array().map(|ps| ps.iter().map(triple).collect()).unwrap_or_default()).collect()
        })
        .unwrap_or_default();
    Ok(Side {
        moments,
        seconds: info["render_seconds"].as_f64().unwrap_or(f64::NAN),
        spp: info["spp"].as_u64().unwrap_or(0) as u32,
        label: format!("mitsuba {variant}"),
        region_pass_means,
    })
}

/// [`mitsuba_side`] with the project's `.venv` and driver; `work` is removed afterwards.
pub fn mitsuba_side_in_venv(
    scene: &Path,
    variant: &str,
    plan: &PassPlan,
    work: &Path,
    progress: &dyn Fn(u32),
) -> Result<Side, String> {
    let root = repo_root();
    let side = mitsuba_side(
        &root.join(".venv/bin/python"),
        &root.join("validation/mitsuba_passes.py"),
        scene,
        variant,
        plan,
        work,
        progress,
    );
    let _ = std::fs::remove_dir_all(work);
    side
}

/// The repository root (where `.venv` and `validation/` live): `MATTE_ROOT`, else the
/// source tree this binary was built from.
pub fn repo_root() -> PathBuf {
    std::env::var_os("MATTE_ROOT").map(PathBuf::from).unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")))
}
