//! `matte bench`: the speed targets (docs/performance.md) measured in one run on this machine: matte's
//! renderer against Mitsuba (`scalar_rgb`, `llvm_ad_rgb` with a warm kernel cache) on
//! the same scenes at the same spp (and with matte's two tile drivers), samples/s against spp,
//! BVH build share, each diffuse model's render time against Lambert's, kernel ns/eval against
//! Lambert, and each traced plugin's render time against Mitsuba's `diffuse` (llvm_ad_rgb).

pub mod kernels;
pub mod mitsuba;
pub mod render;
pub mod report;
pub mod sampling;
pub mod traversal;

use render::RenderJob;
use std::path::PathBuf;

#[derive(Clone, Debug)]
pub struct BenchOptions {
    /// Small images and one repeat: checks the machinery, not the targets.
    pub quick: bool,
    pub repeats: u32,
    /// Time Mitsuba too (needs the Python side, [`crate::installation`]).
    pub mitsuba: bool,
    pub out: PathBuf,
    /// The bundled scenes (`matte bench` gives the installation's, [`crate::installation::scenes_dir`]).
    pub scenes: PathBuf,
}

/// The scenes of the renderer targets, all diffuse surfaces as Mitsuba's built-in `diffuse`
/// (so Mitsuba runs its own code, not a plugin): the Cornell box with unbounded paths, and
/// the study's bunny (two point lights, `direct`) and room (glass, metal, unbounded paths),
/// from the bundled scenes in `root`.
pub fn render_jobs(quick: bool, root: &std::path::Path) -> Vec<RenderJob> {
    let (res, spp) = if quick { ("32", 4) } else { ("256", 64) };
    let job = |name: &str, file: &str, extra: &[(&str, &str)]| {
        let mut defines = vec![("res".to_string(), res.to_string())];
        defines.extend(extra.iter().map(|(k, v)| (k.to_string(), v.to_string())));
        RenderJob { name: name.into(), scene: root.join(file), defines, spp }
    };
    vec![
        job("cornell", "cornell_box.xml", &[("max_depth", "-1")]),
        job("bunny", "study/bunny.xml", &[("bsdf", "diffuse")]),
        job("room", "study/room.xml", &[("bsdf", "diffuse")]),
    ]
}

/// Everything `matte bench` measured.
#[derive(Clone, Debug)]
pub struct Measurements {
    pub jobs: Vec<(RenderJob, render::MatteTime)>,
    pub mitsuba: Option<mitsuba::MitsubaTimes>,
    /// Cornell box samples/s at increasing spp.
    pub scaling: Vec<(u32, f64)>,
    pub kernels: Vec<kernels::KernelTime>,
    /// The generic kernels in f32 and 8-wide (ns per pair).
    pub wide_kernels: Vec<kernels::WideKernelTime>,
    /// Per scene: ns per ray of each mesh backend on the same rays.
    pub traversal: Vec<(String, Vec<traversal::TraversalTime>)>,
    /// The room's render seconds with each diffuse model ([`render::time_models`]).
    pub models: Vec<(String, f64)>,
}

pub const MITSUBA_VARIANTS: [&str; 2] = ["scalar_rgb", "llvm_ad_rgb"];

/// Runs every measurement; `progress` gets a line per step.
pub fn run(opts: &BenchOptions, progress: &dyn Fn(&str)) -> Result<Measurements, String> {
    let jobs = render_jobs(opts.quick, &opts.scenes);
    let repeats = if opts.quick { 1 } else { opts.repeats };
    progress("kernels");
    let kernels = kernels::time_kernels(repeats);
    let wide_kernels = kernels::time_wide_kernels(repeats);
    let mut timed = Vec::new();
    for job in &jobs {
        progress(&format!("matte {}", job.name));
        timed.push((job.clone(), render::time_matte(job, repeats)?));
    }
    progress("matte: each diffuse model against Lambert (room)");
    let models = if opts.quick {
        render::time_models(&opts.scenes, 16, 2, 1)?
    } else {
        render::time_models(&opts.scenes, 128, 64, repeats)?
    };
    progress("traversal: Embree and CWBVH on the same rays");
    let mut traversal = Vec::new();
    for job in &jobs {
        let loaded = matte_render::load::load_file(&job.scene, &job.defines).map_err(|e| e.to_string())?;
        let paths = if opts.quick { 2_000 } else { 100_000 };
        traversal.push((job.name.clone(), traversal::time_traversal(&loaded, paths, repeats)));
    }
    progress("matte spp scaling");
    let mut scaling_job = jobs[0].clone();
    scaling_job.defines[0].1 = if opts.quick { "16".into() } else { "128".into() };
    let scaling = render::spp_scaling(&scaling_job, if opts.quick { &[1, 4] } else { &[16, 64, 256] }, repeats)?;
    let mitsuba = if opts.mitsuba {
        let variants: Vec<String> = MITSUBA_VARIANTS.iter().map(|v| v.to_string()).collect();
        let plugin = if opts.quick { (32, 4) } else { (256, 64) };
        Some(mitsuba::time_mitsuba(&jobs, &variants, repeats, Some(plugin), &opts.out)?)
    } else {
        None
    };
    Ok(Measurements { jobs: timed, mitsuba, scaling, kernels, wide_kernels, traversal, models })
}
