//! The bench's table, its targets (docs/performance.md) with pass/fail, and the JSON record.

use super::Measurements;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// One target: what, the measured value, the limit (measured ≤ limit passes, except where
/// `at_least`), and whether it holds.
#[derive(Clone, Debug)]
pub struct SpeedTarget {
    pub what: String,
    pub measured: f64,
    pub limit: f64,
    pub at_least: bool,
}

impl SpeedTarget {
    pub fn met(&self) -> bool {
        if self.at_least { self.measured >= self.limit } else { self.measured <= self.limit }
    }
}

/// The speed targets (docs/performance.md) that the measurements can check.
pub fn targets(m: &Measurements) -> Vec<SpeedTarget> {
    let mut t = Vec::new();
    let le = |what: String, measured: f64, limit: f64| SpeedTarget { what, measured, limit, at_least: false };
    if let Some(mi) = &m.mitsuba {
        for (job, mt) in &m.jobs {
            if let Some(s) = mi.seconds(&job.name, "llvm_ad_rgb") {
                t.push(le(format!("{}: matte / llvm_ad_rgb time", job.name), mt.seconds / s, 0.8));
            }
            if let Some(s) = mi.seconds(&job.name, "scalar_rgb") {
                t.push(le(format!("{}: matte / scalar_rgb time", job.name), mt.seconds / s, 0.4));
            }
        }
        for (kind, ratio) in mi.plugin_ratios() {
            t.push(le(format!("plugin {kind} / diffuse time (llvm_ad_rgb, symbolic)"), ratio, plugin_limit(&kind)));
        }
    }
    if let (Some(lo), Some(hi)) =
        (m.scaling.iter().map(|s| s.1).min_by(f64::total_cmp), m.scaling.iter().map(|s| s.1).max_by(f64::total_cmp))
    {
        t.push(SpeedTarget {
            what: "Cornell samples/s: slowest / fastest over spp".into(),
            measured: lo / hi,
            limit: 0.9,
            at_least: true,
        });
    }
    if let Some((_, lambert)) = m.models.iter().find(|(k, _)| k == "lambert") {
        for (model, sec) in m.models.iter().filter(|(k, _)| k != "lambert") {
            t.push(le(format!("room: render with {model} / with lambert"), sec / lambert, 1.1));
        }
    }
    if let Some((job, mt)) = m.jobs.iter().find(|(j, _)| j.name == "bunny") {
        t.push(le(format!("{}: BVH build / render time", job.name), mt.accel_build_seconds / mt.seconds, 0.10));
    }
    if let Some(lambert) = m.kernels.iter().find(|k| k.model == "lambert") {
        for k in m.kernels.iter().filter(|k| k.model != "lambert") {
            let limit = if k.model == "ginneken" { 4.0 } else { 2.0 };
            t.push(le(format!("kernel {}: ns/eval / Lambert's", k.model), k.ns_per_eval / lambert.ns_per_eval, limit));
        }
    }
    t
}

/// The traced plugins' render-time limits against `diffuse` (docs/performance.md, plugins): the
/// extra operations each model records into the path tracer's kernel.
fn plugin_limit(kind: &str) -> f64 {
    match kind {
        "lambert" => 1.02,
        "oren_nayar" => 1.05,
        _ => 1.10,
    }
}

/// CPU model and core count, for the record.
pub fn machine() -> String {
    let cpu = cpu_model().unwrap_or_else(|| "unknown CPU".into());
    format!("{cpu}, {} threads", rayon::current_num_threads())
}

/// The CPU's model name: Linux's `/proc/cpuinfo` (and any other system that has one).
#[cfg(not(any(target_os = "macos", windows)))]
fn cpu_model() -> Option<String> {
    model_name(&std::fs::read_to_string("/proc/cpuinfo").ok()?)
}

/// The CPU's model name: macOS's `sysctl machdep.cpu.brand_string` ("Apple M2", "Intel(R) …").
#[cfg(target_os = "macos")]
fn cpu_model() -> Option<String> {
    let out = std::process::Command::new("/usr/sbin/sysctl").args(["-n", "machdep.cpu.brand_string"]).output().ok()?;
    let name = String::from_utf8_lossy(&out.stdout).trim().to_string();
    (out.status.success() && !name.is_empty()).then_some(name)
}

/// The CPU's model: Windows's `PROCESSOR_IDENTIFIER` ("Intel64 Family 6 Model 158 …").
#[cfg(windows)]
fn cpu_model() -> Option<String> {
    std::env::var("PROCESSOR_IDENTIFIER").ok().map(|s| s.trim().to_string()).filter(|s| !s.is_empty())
}

/// The `model name` of a `/proc/cpuinfo`.
#[cfg_attr(any(target_os = "macos", windows), allow(dead_code))]
fn model_name(cpuinfo: &str) -> Option<String> {
    cpuinfo
        .lines()
        .find(|l| l.starts_with("model name"))
        .and_then(|l| l.split(':').nth(1))
        .map(|s| s.trim().to_string())
}

/// The human-readable table (also what docs/performance.md shows).
pub fn table(m: &Measurements) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(s, "machine: {}", machine());
    let _ = writeln!(
        s,
        "\n| scene | res, spp | matte s ({} driver) | Mrays/s | matte s, {} driver | matte s, all in CWBVH | scalar_rgb s | llvm_ad_rgb s | matte/scalar | matte/llvm |",
        matte_render::integrator::Driver::default().name(),
        super::render::other_driver().name()
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
    for (job, mt) in &m.jobs {
        let res = job.defines.iter().find(|d| d.0 == "res").map_or("?", |d| d.1.as_str());
        let mi = |v: &str| m.mitsuba.as_ref().and_then(|mi| mi.seconds(&job.name, v));
        let cell = |x: Option<f64>, f: &dyn Fn(f64) -> String| x.map_or("—".to_string(), f);
        let _ = writeln!(
            s,
            "| {} | {res}², {} | {:.3} ({}) | {:.2} | {:.3} | {} | {} | {} | {} | {} |",
            job.name,
            job.spp,
            mt.seconds,
            mt.backend.name(),
            mt.rays as f64 / mt.seconds / 1e6,
            mt.other_driver_seconds,
            cell(mt.cwbvh_seconds, &|x| format!("{x:.3}")),
            cell(mi("scalar_rgb"), &|x| format!("{x:.3}")),
            cell(mi("llvm_ad_rgb"), &|x| format!("{x:.3}")),
            cell(mi("scalar_rgb"), &|x| format!("{:.2}×", mt.seconds / x)),
            cell(mi("llvm_ad_rgb"), &|x| format!("{:.2}×", mt.seconds / x)),
        );
    }
    let _ = writeln!(
        s,
        "\n| scene | backend | ns/ray (closest hit) | ns/ray, 8 per call | ns/shadow ray | rays, shadow rays |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for (scene, times) in &m.traversal {
        for t in times {
            let _ = writeln!(
                s,
                "| {scene} | {} | {:.1} | {:.1} | {:.1} | {}, {} |",
                t.backend.name(),
                t.ns_per_ray,
                t.ns_per_ray_packet8,
                t.ns_per_shadow_ray,
                t.rays,
                t.shadow_rays
            );
        }
    }
    let names = matte_render::integrator::wavefront::StageTicks::NAMES;
    let _ = writeln!(s, "\n| where matte's time goes (share of thread time) | {} |", names.join(" | "));
    let _ = writeln!(s, "|---|{}", "---|".repeat(names.len()));
    for (job, mt) in &m.jobs {
        if let Some(f) = mt.stage_fractions {
            let cells: Vec<String> = f.iter().map(|x| format!("{:.1} %", 100.0 * x)).collect();
            let _ = writeln!(s, "| {} | {} |", job.name, cells.join(" | "));
        }
    }
    if let Some((_, lambert)) = m.models.iter().find(|(k, _)| k == "lambert") {
        let _ = writeln!(s, "\n| room 128², 64 spp, every diffuse surface as | s | / Lambert |");
        let _ = writeln!(s, "|---|---|---|");
        for (model, sec) in &m.models {
            let _ = writeln!(s, "| {model} | {sec:.3} | {:.3}× |", sec / lambert);
        }
    }
    let _ = writeln!(s, "\n| kernel | ns/eval (RGB) | / Lambert |");
    let _ = writeln!(s, "|---|---|---|");
    let lambert = m.kernels.iter().find(|k| k.model == "lambert").map_or(f64::NAN, |k| k.ns_per_eval);
    for k in &m.kernels {
        let _ = writeln!(s, "| {} | {:.2} | {:.2}× |", k.model, k.ns_per_eval, k.ns_per_eval / lambert);
    }
    let _ = writeln!(s, "\n| kernel (generic, RGB) | f32 ns/pair | f32x8 ns/pair | speed-up |");
    let _ = writeln!(s, "|---|---|---|---|");
    for k in &m.wide_kernels {
        let _ = writeln!(s, "| {} | {:.2} | {:.2} | {:.1}× |", k.model, k.f32_ns, k.f32x8_ns, k.f32_ns / k.f32x8_ns);
    }
    let _ = writeln!(
        s,
        "\nCornell box samples/s by spp: {}",
        m.scaling.iter().map(|(n, r)| format!("{n} spp {:.3} M/s", r / 1e6)).collect::<Vec<_>>().join(", ")
    );
    if let Some(mi) = m.mitsuba.as_ref().filter(|mi| !mi.plugin.is_empty()) {
        let times: Vec<String> = mi.plugin.iter().map(|(k, sec)| format!("{k} {sec:.3} s")).collect();
        let _ = writeln!(s, "Mitsuba llvm_ad_rgb (symbolic) Cornell box, one process per type: {}", times.join(", "));
    }
    let _ = writeln!(s, "\n| target | measured | limit | met |");
    let _ = writeln!(s, "|---|---|---|---|");
    for t in targets(m) {
        let _ = writeln!(
            s,
            "| {} | {:.3} | {} {} | {} |",
            t.what,
            t.measured,
            if t.at_least { "≥" } else { "≤" },
            t.limit,
            if t.met() { "yes" } else { "**no**" }
        );
    }
    s
}

/// bench.json.
#[derive(Serialize)]
pub struct BenchJson {
    pub machine: String,
    pub renders: Vec<RenderJson>,
    pub spp_scaling: Vec<ScalingJson>,
    pub kernels: Vec<KernelJson>,
    pub traversal: Vec<TraversalJson>,
    pub wide_kernels: Vec<WideKernelJson>,
    /// The room (128², 64 spp) rendered with every diffuse surface as each model: best seconds.
    pub model_render_seconds: BTreeMap<String, f64>,
    /// Best seconds per plugin type (`diffuse` and matte's), Cornell box, llvm_ad_rgb.
    pub plugin_seconds_llvm_ad_rgb: Option<BTreeMap<String, f64>>,
    pub targets: Vec<TargetJson>,
}

#[derive(Serialize)]
pub struct RenderJson {
    pub name: String,
    pub scene: PathBuf,
    /// `name=value` per `-D` parameter.
    pub defines: Vec<String>,
    pub spp: u32,
    pub matte_seconds: f64,
    pub matte_rays_per_second: f64,
    pub matte_samples_per_second: f64,
    pub accel_build_seconds: f64,
    pub threads: usize,
    /// The structure that traced the meshes (`embree` or `cwbvh`).
    pub accel: &'static str,
    /// The tile driver of `matte_seconds` (`one path` or `wavefront`).
    pub driver: &'static str,
    /// The other tile driver, and its best seconds.
    pub other_driver: &'static str,
    pub matte_seconds_other_driver: f64,
    /// Share of each stage of matte's render (stage name → fraction of thread time).
    pub matte_stage_fractions: Option<BTreeMap<&'static str, f64>>,
    /// Best seconds with the meshes in the CWBVH (when `accel` is `embree`).
    pub matte_seconds_cwbvh: Option<f64>,
    /// Best seconds per Mitsuba variant (none when Mitsuba did not run).
    pub mitsuba_seconds: BTreeMap<&'static str, Option<f64>>,
}

#[derive(Serialize)]
pub struct ScalingJson {
    pub spp: u32,
    pub samples_per_second: f64,
}

#[derive(Serialize)]
pub struct TraversalJson {
    pub scene: String,
    pub backend: &'static str,
    pub ns_per_ray: f64,
    pub ns_per_shadow_ray: f64,
    pub ns_per_ray_packet8: f64,
    pub rays: usize,
    pub shadow_rays: usize,
}

#[derive(Serialize)]
pub struct WideKernelJson {
    pub model: &'static str,
    pub f32_ns_per_pair: f64,
    pub f32x8_ns_per_pair: f64,
}

#[derive(Serialize)]
pub struct KernelJson {
    pub model: &'static str,
    pub ns_per_eval: f64,
}

#[derive(Serialize)]
pub struct TargetJson {
    pub what: String,
    pub measured: f64,
    pub limit: f64,
    pub at_least: bool,
    pub met: bool,
}

pub fn json(m: &Measurements) -> BenchJson {
    BenchJson {
        machine: machine(),
        renders: m
            .jobs
            .iter()
            .map(|(job, mt)| RenderJson {
                name: job.name.clone(),
                scene: job.scene.clone(),
                defines: job.defines.iter().map(|(k, v)| format!("{k}={v}")).collect(),
                spp: job.spp,
                matte_seconds: mt.seconds,
                matte_rays_per_second: mt.rays as f64 / mt.seconds,
                matte_samples_per_second: mt.samples as f64 / mt.seconds,
                accel_build_seconds: mt.accel_build_seconds,
                threads: mt.threads,
                accel: mt.backend.name(),
                driver: matte_render::integrator::Driver::default().name(),
                other_driver: super::render::other_driver().name(),
                matte_seconds_other_driver: mt.other_driver_seconds,
                matte_stage_fractions: mt
                    .stage_fractions
                    .map(|f| matte_render::integrator::wavefront::StageTicks::NAMES.into_iter().zip(f).collect()),
                matte_seconds_cwbvh: mt.cwbvh_seconds,
                mitsuba_seconds: super::MITSUBA_VARIANTS
                    .iter()
                    .map(|v| (*v, m.mitsuba.as_ref().and_then(|mi| mi.seconds(&job.name, v))))
                    .collect(),
            })
            .collect(),
        spp_scaling: m.scaling.iter().map(|(n, r)| ScalingJson { spp: *n, samples_per_second: *r }).collect(),
        kernels: m.kernels.iter().map(|k| KernelJson { model: k.model, ns_per_eval: k.ns_per_eval }).collect(),
        traversal: m
            .traversal
            .iter()
            .flat_map(|(scene, times)| {
                times.iter().map(|t| TraversalJson {
                    scene: scene.clone(),
                    backend: t.backend.name(),
                    ns_per_ray: t.ns_per_ray,
                    ns_per_shadow_ray: t.ns_per_shadow_ray,
                    ns_per_ray_packet8: t.ns_per_ray_packet8,
                    rays: t.rays,
                    shadow_rays: t.shadow_rays,
                })
            })
            .collect(),
        wide_kernels: m
            .wide_kernels
            .iter()
            .map(|k| WideKernelJson { model: k.model, f32_ns_per_pair: k.f32_ns, f32x8_ns_per_pair: k.f32x8_ns })
            .collect(),
        model_render_seconds: m.models.iter().cloned().collect(),
        plugin_seconds_llvm_ad_rgb: m.mitsuba.as_ref().map(|mi| mi.plugin.iter().cloned().collect()),
        targets: targets(m)
            .into_iter()
            .map(|t| TargetJson {
                met: t.met(),
                what: t.what,
                measured: t.measured,
                limit: t.limit,
                at_least: t.at_least,
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_model_name_is_cpuinfos_first() {
        let cpuinfo = "processor\t: 0\nvendor_id\t: GenuineIntel\nmodel name\t: Intel(R) Xeon(R) CPU @ 2.20GHz\n\
                       processor\t: 1\nmodel name\t: Intel(R) Xeon(R) CPU @ 2.20GHz\n";
        assert_eq!(model_name(cpuinfo).as_deref(), Some("Intel(R) Xeon(R) CPU @ 2.20GHz"));
        // aarch64 Linux has no model name.
        assert_eq!(model_name("processor\t: 0\nBogoMIPS\t: 50.00\nCPU implementer\t: 0x41\n"), None);
        assert!(machine().ends_with(&format!(", {} threads", rayon::current_num_threads())));
    }
}
