//! `<integrator>`: Mitsuba's `path` (max_depth −1, rr_depth 5, hide_emitters false; also
//! `volpath` and `volpathmis`, which equal it on surfaces), and
//! `direct` (emitter_samples = bsdf_samples = shading_samples = 1), `ptracer` (max_depth −1,
//! rr_depth 5, hide_emitters false, samples_per_pass read and ignored), and `moment`
//! (`src/integrators/moment.cpp`): its image is the first nested integrator's, sample by
//! sample; the second-moment AOVs it adds are not produced. Every nested integrator is still
//! built, so an invalid one is reported.

use super::{err, values};
use crate::integrator::{DirectIntegrator, Integrator, ParticleTracer, PathIntegrator};
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

pub fn build(obj: &SceneObject) -> Result<Integrator, SceneError> {
    let integrator = match obj.plugin.as_str() {
        // `volpath` and `volpathmis` on a scene without media (matte refuses media, see
        // `scope.rs`) sample the same surface paths as `path`, with the same MIS weights and
        // Russian roulette, so their expected image is `path`'s; `use_spectral_mis` only
        // weighs wavelengths inside media.
        "path" | "volpath" | "volpathmis" => {
            if obj.plugin == "volpathmis" {
                let _ = values::boolean(obj, "use_spectral_mis", true)?;
            }
            let max_depth = values::integer(obj, "max_depth", -1, -1, u32::MAX as i64)?;
            let rr_depth = values::integer(obj, "rr_depth", 5, 1, u32::MAX as i64)?;
            Integrator::Path(PathIntegrator {
                max_depth: if max_depth < 0 { u32::MAX } else { max_depth as u32 },
                rr_depth: rr_depth as u32,
                hide_emitters: values::boolean(obj, "hide_emitters", false)?,
            })
        }
        "direct" => {
            let shading = obj.properties.integer("shading_samples")?;
            let (ne, nb) = match shading {
                Some(n) => {
                    if obj.properties.contains("emitter_samples") || obj.properties.contains("bsdf_samples") {
                        return Err(err(
                            obj,
                            "shading_samples cannot be combined with emitter_samples or bsdf_samples",
                        ));
                    }
                    (n, n)
                }
                None => (
                    values::integer(obj, "emitter_samples", 1, 0, 1 << 20)?,
                    values::integer(obj, "bsdf_samples", 1, 0, 1 << 20)?,
                ),
            };
            if ne < 0 || nb < 0 || ne + nb == 0 {
                return Err(err(obj, "needs at least one emitter or BSDF sample"));
            }
            Integrator::Direct(DirectIntegrator {
                emitter_samples: ne as u32,
                bsdf_samples: nb as u32,
                hide_emitters: values::boolean(obj, "hide_emitters", false)?,
            })
        }
        "ptracer" => {
            let max_depth = values::integer(obj, "max_depth", -1, -1, u32::MAX as i64)?;
            let rr_depth = values::integer(obj, "rr_depth", 5, 1, u32::MAX as i64)?;
            let _ = values::integer(obj, "samples_per_pass", -1, -1, u32::MAX as i64)?;
            Integrator::ParticleTracer(ParticleTracer {
                max_depth: if max_depth < 0 { u32::MAX } else { max_depth as u32 },
                rr_depth: rr_depth as u32,
                hide_emitters: values::boolean(obj, "hide_emitters", false)?,
            })
        }
        "moment" => {
            let mut first = None;
            for child in obj.children_with_tag("integrator") {
                let nested = build(&child.object)?;
                first.get_or_insert(nested);
            }
            first.ok_or_else(|| err(obj, "needs at least one nested <integrator>"))?
        }
        other => {
            return Err(err(
                obj,
                format!(
                    "unsupported integrator type \"{other}\" (matte renders: path, volpath, volpathmis, direct, ptracer, moment)"
                ),
            ));
        }
    };
    obj.check_all_used()?;
    Ok(integrator)
}
