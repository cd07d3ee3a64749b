//! Mitsuba's side of `matte bench`, run as `python -m matte_mitsuba.bench` in the Python
//! environment matte is installed in ([`crate::installation`]): render times per job and variant, and each matte plugin's render time
//! against the built-in `diffuse` (llvm_ad_rgb, symbolic, one process per type).

use super::render::RenderJob;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Stdio;

/// One entry of the job list `matte_mitsuba.bench --jobs` reads.
#[derive(Serialize)]
struct JobJson<'a> {
    name: &'a str,
    scene: &'a Path,
    defines: BTreeMap<&'a str, &'a str>,
    spp: u32,
}

/// What `matte_mitsuba.bench` prints.
#[derive(Deserialize)]
struct TimesJson {
    renders: Vec<RenderTimeJson>,
    #[serde(default)]
    plugin: Option<PluginTimesJson>,
}

#[derive(Deserialize)]
struct RenderTimeJson {
    name: String,
    variant: String,
    seconds: f64,
}

#[derive(Deserialize)]
struct PluginTimesJson {
    /// Best seconds per plugin type (`diffuse` and matte's).
    seconds: BTreeMap<String, f64>,
}

#[derive(Clone, Debug, Default)]
pub struct MitsubaTimes {
    /// (job name, variant, best seconds).
    pub renders: Vec<(String, String, f64)>,
    /// (type, best seconds) for `diffuse` and every matte type: the Cornell box in
    /// llvm_ad_rgb's symbolic mode.
    pub plugin: Vec<(String, f64)>,
}

impl MitsubaTimes {
    pub fn seconds(&self, job: &str, variant: &str) -> Option<f64> {
        self.renders.iter().find(|(j, v, _)| j == job && v == variant).map(|r| r.2)
    }

    /// Each matte type's plugin time divided by `diffuse`'s.
    pub fn plugin_ratios(&self) -> Vec<(String, f64)> {
        let Some(diffuse) = self.plugin.iter().find(|(k, _)| k == "diffuse").map(|p| p.1) else {
            return vec![];
        };
        self.plugin.iter().filter(|(k, _)| k != "diffuse").map(|(k, s)| (k.clone(), s / diffuse)).collect()
    }
}

/// Times every job in every variant (and the plugins when `plugin` is set).
/// `work` receives the job list.
pub fn time_mitsuba(
    jobs: &[RenderJob],
    variants: &[String],
    repeats: u32,
    plugin: Option<(u32, u32)>,
    work: &Path,
) -> Result<MitsubaTimes, String> {
    let python = crate::installation::mitsuba_side()?;
    let list: Vec<JobJson> = jobs
        .iter()
        .map(|j| JobJson {
            name: &j.name,
            scene: &j.scene,
            defines: j.defines.iter().map(|(k, v)| (k.as_str(), v.as_str())).collect(),
            spp: j.spp,
        })
        .collect();
    std::fs::create_dir_all(work).map_err(|e| format!("{}: {e}", work.display()))?;
    let jobs_file = work.join("mitsuba_jobs.json");
    let text = serde_json::to_string_pretty(&list).map_err(|e| format!("{}: {e}", jobs_file.display()))?;
    std::fs::write(&jobs_file, text).map_err(|e| format!("{}: {e}", jobs_file.display()))?;
    let mut cmd = python.module("bench");
    cmd.arg("--jobs").arg(&jobs_file).arg("--repeats").arg(repeats.to_string()).arg("--variants").args(variants);
    if let Some((res, spp)) = plugin {
        cmd.args(["--plugin-res", &res.to_string(), "--plugin-spp", &spp.to_string()]);
    }
    let out = cmd.stderr(Stdio::inherit()).output().map_err(|e| format!("{}: {e}", python.python.display()))?;
    if !out.status.success() {
        return Err(format!("matte_mitsuba.bench failed ({})", out.status));
    }
    let times: TimesJson =
        serde_json::from_slice(&out.stdout).map_err(|e| format!("matte_mitsuba.bench printed unexpected JSON: {e}"))?;
    let renders = times.renders.into_iter().map(|r| (r.name, r.variant, r.seconds)).collect();
    let plugin = times.plugin.map(|p| p.seconds.into_iter().collect()).unwrap_or_default();
    Ok(MitsubaTimes { renders, plugin })
}
