//! `matte render SCENE.xml`: renders a Mitsuba XML scene with the Rust path tracer, writes
//! an RGB float EXR (and optionally a tone-mapped sRGB PNG), and prints what it measured
//! (samples/s, rays/s) as JSON.

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use matte_render::film::SplatWeights;
use matte_render::image_io;
use matte_render::integrator::Driver;
use matte_render::load;
use matte_render::renderer;
use serde::Serialize;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Mitsuba 3 XML scene.
    pub scene: PathBuf,
    /// Output EXR (default: the scene's name with .exr, in the current folder).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Samples per pixel (default: the scene sampler's sample_count), rounded as the scene's
    /// sampler rounds its sample_count.
    #[arg(long)]
    pub spp: Option<u32>,
    /// Sampler seed (default: the scene sampler's seed).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Scene parameter, as Mitsuba's `-D name=value` (repeatable).
    #[arg(short = 'D', value_name = "NAME=VALUE")]
    pub define: Vec<String>,
    /// How the film weights samples: `discretized` (the filter's step table, as Mitsuba's
    /// scalar variants) or `exact` (the kernel itself, as its llvm/cuda variants); they differ
    /// at sharp edges (docs/validation.md).
    #[arg(long, value_name = "WEIGHTS", default_value = "discretized", value_parser = SplatWeights::parse)]
    pub splat_weights: SplatWeights,
    /// How each thread runs the integrator over its tiles: `one-path` (one path at a time, the
    /// default) or `wavefront` (32 paths in flight, rays traced eight per query); the image is
    /// the same estimator (docs/performance.md).
    #[arg(long, value_name = "DRIVER", value_parser = Driver::parse)]
    pub driver: Option<Driver>,
    /// Also write a tone-mapped sRGB PNG next to the EXR (same name, .png).
    #[arg(long)]
    pub png: bool,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// No progress bar.
    #[arg(short, long)]
    pub quiet: bool,
}

/// `name=value` pairs from `-D` arguments.
pub fn parse_defines(defs: &[String]) -> Result<Vec<(String, String)>, String> {
    defs.iter()
        .map(|d| match d.split_once('=') {
            Some((k, v)) if !k.trim().is_empty() => Ok((k.trim().to_string(), v.to_string())),
            _ => Err(format!("-D expects NAME=VALUE, got \"{d}\"")),
        })
        .collect()
}

/// What `matte render` prints (JSON) after writing the image.
#[derive(Serialize)]
struct RenderReport<'a> {
    scene: &'a Path,
    output: &'a Path,
    png: Option<&'a Path>,
    width: u32,
    height: u32,
    spp: u32,
    seed: u64,
    threads: usize,
    primitives: usize,
    load_seconds: f64,
    render_seconds: f64,
    samples: u64,
    rays: u64,
    samples_per_second: f64,
    rays_per_second: f64,
    invalid_samples: u64,
}

pub fn run(a: &RenderArgs) -> Result<(), String> {
    let defines = parse_defines(&a.define)?;
    if let Some(n) = a.threads {
        rayon::ThreadPoolBuilder::new().num_threads(n).build_global().map_err(|e| e.to_string())?;
    }
    let t0 = std::time::Instant::now();
    let loaded = load::load_file(&a.scene, &defines).map_err(|e| e.to_string())?;
    let load_seconds = t0.elapsed().as_secs_f64();
    for note in &loaded.notes {
        eprintln!("note: {note}");
    }
    if a.spp == Some(0) {
        return Err("--spp must be at least 1".into());
    }
    // --spp is rounded as the scene's sampler rounds it (Mitsuba's `render(spp=…)`).
    let mut sampling = loaded.sampling;
    if let Some(n) = a.spp {
        sampling = sampling.with_spp(n);
    }
    if let Some(s) = a.seed {
        sampling = sampling.with_seed(s);
    }
    let (spp, seed) = (sampling.spp, sampling.seed);
    let output = a.output.clone().unwrap_or_else(|| {
        PathBuf::from(a.scene.file_stem().map(|s| s.to_os_string()).unwrap_or_else(|| "render".into()))
            .with_extension("exr")
    });
    let bar = if a.quiet || !std::io::stderr().is_terminal() {
        ProgressBar::hidden()
    } else {
        let b = ProgressBar::new(0);
        b.set_style(
            ProgressStyle::with_template("{msg} [{bar:40}] {percent:>3}% {elapsed} (eta {eta})")
                .expect("template")
                .progress_chars("=> "),
        );
        b.set_message(format!("rendering {}", a.scene.display()));
        b
    };
    let progress = |done: u64, total: u64| {
        bar.set_length(total);
        bar.set_position(done);
    };
    let (image, stats) = renderer::render_with(
        &loaded.scene,
        &loaded.integrator,
        &loaded.camera,
        loaded.film.with_splat_weights(a.splat_weights),
        sampling,
        a.driver.unwrap_or_default(),
        &progress,
    );
    bar.finish_and_clear();
    image_io::write_exr(&output, &image).map_err(|e| format!("{}: {e}", output.display()))?;
    let png = a.png.then(|| output.with_extension("png"));
    if let Some(p) = &png {
        image_io::write_png(p, &image).map_err(|e| format!("{}: {e}", p.display()))?;
    }
    let report = RenderReport {
        scene: &a.scene,
        output: &output,
        png: png.as_deref(),
        width: image.width,
        height: image.height,
        spp,
        seed,
        threads: rayon::current_num_threads(),
        primitives: loaded.scene.primitive_count(),
        load_seconds,
        render_seconds: stats.seconds,
        samples: stats.samples,
        rays: stats.rays,
        samples_per_second: stats.samples as f64 / stats.seconds,
        rays_per_second: stats.rays as f64 / stats.seconds,
        invalid_samples: stats.invalid_samples,
    };
    println!("{}", serde_json::to_string_pretty(&report).map_err(|e| format!("JSON output: {e}"))?);
    Ok(())
}
