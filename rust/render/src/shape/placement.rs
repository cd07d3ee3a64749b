//! [`Placement`]: what Mitsuba's `Shape` base class reads for every shape before the shape's own
//! properties (`src/render/shape.cpp`).

use crate::load::props::PluginProps;
use glam::Affine3A;
use matte_scene_file::SceneError;

/// What Mitsuba's `Shape` base class reads for every shape (`src/render/shape.cpp`):
/// `to_world` (here after the transform of the `instance` placing the shape, if any) and
/// `flip_normals`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Placement {
    pub to_world: Affine3A,
    pub flip_normals: bool,
}

impl Placement {
    /// Reads `to_world` and `flip_normals`; `outer` is the placing instance's transform (the
    /// identity outside a shape group).
    pub(crate) fn from_props(p: &mut PluginProps, outer: Affine3A) -> Result<Self, SceneError> {
        let to_world = outer * p.transform("to_world")?;
        Ok(Placement { to_world, flip_normals: p.boolean("flip_normals")? })
    }
}
