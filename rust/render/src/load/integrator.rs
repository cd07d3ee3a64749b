//! `<integrator>`: which type builds each plugin name. `path` (also `volpath` and
//! `volpathmis`, which equal it on surfaces), `direct` and `ptracer` read their own properties
//! (`from_props` in `rust/render/src/integrator/`, through [`PluginProps`]); `moment`
//! (`src/integrators/moment.cpp`) is built here: it has no type of its own (its image is the
//! first nested integrator's, sample by sample; the second-moment AOVs it adds are not
//! produced) and reads nothing but its nested integrators, which this dispatch builds. Every
//! nested integrator is still built, so an invalid one is reported.

use super::props::{FromProps, PluginProps};
use super::{Builder, err};
use crate::integrator::{DirectIntegrator, Integrator, ParticleTracer, PathIntegrator};
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

/// `T::from_props` as an [`Integrator`].
fn make<T: FromProps + Into<Integrator>>(p: &mut PluginProps) -> Result<Integrator, SceneError> {
    T::from_props(p).map(Into::into)
}

/// The integrator of `obj`.
pub fn build(b: &Builder, obj: &SceneObject) -> Result<Integrator, SceneError> {
    let build: fn(&mut PluginProps) -> Result<Integrator, SceneError> = match obj.plugin.as_str() {
        "path" | "volpath" | "volpathmis" => make::<PathIntegrator>,
        "direct" => make::<DirectIntegrator>,
        "ptracer" => make::<ParticleTracer>,
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

/// `moment`: the first nested integrator's image; every nested one is built.
fn moment(p: &mut PluginProps) -> Result<Integrator, SceneError> {
    let mut first = None;
    for child in p.nested("integrator") {
        let nested = build(p.builder(), &child)?;
        first.get_or_insert(nested);
    }
    first.ok_or_else(|| p.err("needs at least one nested <integrator>"))
}
