//! The generic object tree: one [`SceneObject`] per object element (`<bsdf>`, `<shape>`, ...),
//! its properties and its nested objects or resolved `<ref>`s. An object referenced from
//! several places is shared (`Rc`), as in Mitsuba where one instance has several parents.

use std::cell::Cell;
use std::collections::HashSet;
use std::rc::Rc;

use super::properties::Properties;
use crate::error::{SceneError, SourcePos};

/// A nested object or a resolved `<ref>` of a [`SceneObject`].
#[derive(Debug)]
pub struct Child {
    /// The `name` attribute of the nested element or `<ref>` (`None` if absent).
    pub name: Option<String>,
    pub object: Rc<SceneObject>,
    /// Of the nested element or the `<ref>`.
    pub pos: SourcePos,
    /// Set by the lookup helpers; [`SceneObject::check_all_used`] reports the ones never used.
    pub used: Cell<bool>,
}

impl Child {
    pub fn mark_used(&self) {
        self.used.set(true);
    }
}

/// One object element of the scene.
#[derive(Debug)]
pub struct SceneObject {
    /// Element name: "scene", "bsdf", "shape", "emitter", "sensor", "film", "rfilter",
    /// "sampler", "integrator", "texture" (also for `<spectrum type=...>`), "medium",
    /// "phase", "volume".
    pub tag: String,
    /// The `type` attribute ("" for `<scene>`).
    pub plugin: String,
    pub id: Option<String>,
    /// Of the element.
    pub pos: SourcePos,
    pub properties: Properties,
    /// Nested objects and resolved `<ref>`s, in document order.
    pub children: Vec<Child>,
    /// Root only: folders added by `<path value="..."/>`, searched (in this order) before
    /// the scene file's folder for relative asset file names, as Mitsuba's file resolver.
    pub search_paths: Vec<std::path::PathBuf>,
}

impl SceneObject {
    /// The child whose `name` attribute is `name`; marks it used.
    pub fn child(&self, name: &str) -> Option<&Child> {
        let c = self.children.iter().find(|c| c.name.as_deref() == Some(name))?;
        c.mark_used();
        Some(c)
    }

    /// Children with element name `tag`, in document order; each is marked used as the
    /// iterator yields it.
    pub fn children_with_tag<'a>(&'a self, tag: &'a str) -> impl Iterator<Item = &'a Child> {
        self.children.iter().filter(move |c| c.object.tag == tag).inspect(|c| c.mark_used())
    }

    /// Error for the first property never queried, then for the first child never used,
    /// e.g. `unexpected nested bsdf of type "diffuse" in emitter plugin of type "point"`.
    /// Checks this object only; see [`SceneObject::check_tree_used`].
    pub fn check_all_used(&self) -> Result<(), SceneError> {
        self.properties.check_all_used(&self.tag, &self.plugin)?;
        match self.children.iter().find(|c| !c.used.get()) {
            None => Ok(()),
            Some(c) => {
                let named = c.name.as_ref().map(|n| format!(" \"{n}\"")).unwrap_or_default();
                Err(SceneError::at(
                    &c.pos,
                    format!(
                        "unexpected nested {}{named} of type \"{}\" in {} plugin of type \"{}\"",
                        c.object.tag, c.object.plugin, self.tag, self.plugin
                    ),
                ))
            }
        }
    }

    /// [`SceneObject::check_all_used`] on this object and everything reachable from it (each
    /// shared object once), depth first in document order. Run after building the scene.
    pub fn check_tree_used(&self) -> Result<(), SceneError> {
        let mut seen: HashSet<*const SceneObject> = HashSet::new();
        let mut stack: Vec<&SceneObject> = vec![self];
        while let Some(o) = stack.pop() {
            if !seen.insert(o as *const SceneObject) {
                continue;
            }
            o.check_all_used()?;
            stack.extend(o.children.iter().rev().map(|c| &*c.object));
        }
        Ok(())
    }
}
