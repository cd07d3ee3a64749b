//! `shapegroup` and `instance` (`src/shapes/shapegroup.cpp`, `src/shapes/instance.cpp`): a
//! group's shapes are not rendered by themselves; every `instance` of it places all of them
//! with its `to_world` in front of each shape's own. matte flattens the instances into
//! world-space copies (same images as Mitsuba's two-level BVH; memory grows with the
//! instance count). As in Mitsuba, groups cannot nest and grouped shapes cannot emit light.
//! Both are declared with the shape family in `load/shape.rs`, on which this file builds.

use super::builder::{Builder, err};
use super::props::PluginProps;
use super::shape;
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

/// A top-level `shapegroup`: only shapes inside, no nested groups or instances.
pub fn check_group(obj: &SceneObject) -> Result<(), SceneError> {
    for child in &obj.children {
        child.mark_used();
        let c = &child.object;
        if c.tag != "shape" {
            return Err(err(c, format!("a <{}> cannot be nested in a shapegroup", c.tag)));
        }
        if c.plugin == "shapegroup" || c.plugin == "instance" {
            return Err(err(c, "nested instancing is not permitted"));
        }
    }
    obj.check_all_used()
}

/// An `instance`: exactly one referenced or nested `shapegroup`, and `to_world`.
pub fn build(b: &mut Builder, obj: &SceneObject) -> Result<(), SceneError> {
    let outer = PluginProps::new(b, obj).transform("to_world")?;
    let mut group = None;
    for child in &obj.children {
        child.mark_used();
        let c = &child.object;
        if c.tag != "shape" || c.plugin != "shapegroup" {
            return Err(err(c, "an instance can only contain a reference to a shapegroup"));
        }
        if group.replace(c.clone()).is_some() {
            return Err(err(obj, "an instance can only reference one shapegroup"));
        }
    }
    let group = group.ok_or_else(|| err(obj, "needs a shapegroup (<ref id=\"...\"/>)"))?;
    obj.check_all_used()?;
    check_group(&group)?;
    for child in &group.children {
        shape::build_placed(b, &child.object, outer, true)?;
    }
    Ok(())
}
