//! `<integrator>`: Mitsuba's `path` (max_depth −1, rr_depth 5, hide_emitters false; also
//! `volpath` and `volpathmis`, which equal it on surfaces), and
//! `direct` (emitter_samples = bsdf_samples = shading_samples = 1), `ptracer` (max_depth −1,
//! rr_depth 5, hide_emitters false, samples_per_pass read and ignored), and `moment`
//! (`src/integrators/moment.cpp`): its image is the first nested integrator's, sample by
//! sample; the second-moment AOVs it adds are not produced. Every nested integrator is still
//! built, so an invalid one is reported.

use super::props::PluginProps;
use super::{Builder, err};
use crate::integrator::{DirectIntegrator, Integrator, ParticleTracer, PathIntegrator};
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

/// The integrator of `obj`.
pub fn build(b: &Builder, obj: &SceneObject) -> Result<Integrator, SceneError> {
    let build: fn(&mut PluginProps) -> Result<Integrator, SceneError> = match obj.plugin.as_str() {
        // `volpath` and `volpathmis` on a scene without media (matte refuses media, see
        // `scope.rs`) sample the same surface paths as `path`, with the same MIS weights and
        // Russian roulette, so their expected image is `path`'s; `use_spectral_mis` only
        // weighs wavelengths inside media.
        "path" | "volpath" | "volpathmis" => path,
        "direct" => direct,
        "ptracer" => ptracer,
        "moment" => moment,
        other => {
            return Err(err(
                obj,
                format!(
                    "unsupported integrator type \"{other}\" (matte renders: path, volpath, volpathmis, direct, ptracer, moment)"
                ),
            ));
        }
    };
    let integrator = build(&mut PluginProps::new(b, obj))?;
    obj.check_all_used()?;
    Ok(integrator)
}

/// `max_depth` (−1: unbounded) and `rr_depth` of `MonteCarloIntegrator`
/// (`src/render/integrator.cpp`).
fn depths(p: &mut PluginProps) -> Result<(u32, u32), SceneError> {
    let max_depth = p.integer("max_depth", -1..=u32::MAX as i64)?;
    let rr_depth = p.integer("rr_depth", 1..=u32::MAX as i64)?;
    Ok((if max_depth < 0 { u32::MAX } else { max_depth as u32 }, rr_depth as u32))
}

/// `path`, `volpath`, `volpathmis`.
fn path(p: &mut PluginProps) -> Result<Integrator, SceneError> {
    if p.object().plugin == "volpathmis" {
        let _ = p.boolean("use_spectral_mis")?;
    }
    let (max_depth, rr_depth) = depths(p)?;
    Ok(Integrator::Path(PathIntegrator { max_depth, rr_depth, hide_emitters: p.boolean("hide_emitters")? }))
}

/// `direct` (`src/integrators/direct.cpp`): `shading_samples`, or `emitter_samples` and
/// `bsdf_samples` (default `shading_samples`, 1), not both.
fn direct(p: &mut PluginProps) -> Result<Integrator, SceneError> {
    let (ne, nb) = match p.integer_opt("shading_samples")? {
        Some(n) => {
            if p.has_property("emitter_samples") || p.has_property("bsdf_samples") {
                return Err(p.err("shading_samples cannot be combined with emitter_samples or bsdf_samples"));
            }
            (n, n)
        }
        None => {
            let shading = p.integer("shading_samples", 0..=1 << 20)?;
            (
                p.integer_or("emitter_samples", shading, 0..=1 << 20)?,
                p.integer_or("bsdf_samples", shading, 0..=1 << 20)?,
            )
        }
    };
    if ne < 0 || nb < 0 || ne + nb == 0 {
        return Err(p.err("needs at least one emitter or BSDF sample"));
    }
    let (emitter_samples, bsdf_samples) = (ne as u32, nb as u32);
    Ok(Integrator::Direct(DirectIntegrator {
        emitter_samples,
        bsdf_samples,
        hide_emitters: p.boolean("hide_emitters")?,
    }))
}

/// `ptracer`: `samples_per_pass` (default −1) is read and ignored.
fn ptracer(p: &mut PluginProps) -> Result<Integrator, SceneError> {
    let (max_depth, rr_depth) = depths(p)?;
    let _ = p.integer_or("samples_per_pass", -1, -1..=u32::MAX as i64)?;
    let hide_emitters = p.boolean("hide_emitters")?;
    Ok(Integrator::ParticleTracer(ParticleTracer { max_depth, rr_depth, hide_emitters }))
}

/// `moment`: the first nested integrator's image; every nested one is built.
fn moment(p: &mut PluginProps) -> Result<Integrator, SceneError> {
    let mut first = None;
    for child in p.nested("integrator") {
        let nested = build(p.builder(), &child)?;
        first.get_or_insert(nested);
    }
    first.ok_or_else(|| p.err("needs at least one nested <integrator>"))
}
