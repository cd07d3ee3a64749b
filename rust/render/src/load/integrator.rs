//! `<integrator>`: which type builds each plugin name. `path` (also `volpath` and
//! `volpathmis`, which equal it on surfaces), `direct` and `ptracer` read their own properties
//! (`from_props` in `rust/render/src/integrator/`, through [`PluginProps`]); `moment`
//! (`src/integrators/moment.cpp`) is built here: it has no type of its own (its image is the
//! first nested integrator's, sample by sample; the second-moment AOVs it adds are not
//! produced) and reads nothing but its nested integrators, which this dispatch builds. Every
//! nested integrator is still built, so an invalid one is reported.

use super::builder::{Builder, err};
use super::props::{FromProps, PluginProps};
use crate::integrator::{DirectIntegrator, Integrator, ParticleTracer, PathIntegrator};
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

/// `T::from_props` as an [`Integrator`].
fn make<T: FromProps + Into<Integrator>>(p: &mut PluginProps) -> Result<Integrator, SceneError> {
    T::from_props(p).map(Into::into)
}

plugins! {
    /// Mitsuba 3.9.1's integrator plugins matte builds, each with its type (`moment` with
    /// [`moment`]).
    pub(super) NAMES, INTEGRATORS: fn(&mut PluginProps) -> Result<Integrator, SceneError> = [
        "path" => make::<PathIntegrator>,
        "volpath" => make::<PathIntegrator>,
        "volpathmis" => make::<PathIntegrator>,
        "direct" => make::<DirectIntegrator>,
        "ptracer" => make::<ParticleTracer>,
        "moment" => moment,
    ];
}

/// The integrator of `obj`.
pub fn build(b: &Builder, obj: &SceneObject) -> Result<Integrator, SceneError> {
    let Some(&(_, build)) = INTEGRATORS.iter().find(|(n, _)| *n == obj.plugin) else {
        let message = format!("unsupported integrator type \"{}\" (matte renders: {})", obj.plugin, NAMES.join(", "));
        return Err(err(obj, message));
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
