//! The flat node list the XML walk produces before `<ref>`s are resolved (Mitsuba's
//! `ParserState`, `include/mitsuba/core/parser.h`): nodes refer to each other by index or,
//! for `<ref>`, by id, because a reference may name an object defined further down.

use std::collections::HashMap;

use super::properties::{Properties, Property};
use crate::error::{SceneError, SourcePos};

/// What a child slot points at.
pub(crate) enum Target {
    /// A nested object element: an index into [`RawScene::nodes`].
    Node(usize),
    /// `<ref id=...>`, resolved once the whole scene is read.
    Ref(String),
}

pub(crate) struct RawChild {
    pub name: Option<String>,
    pub target: Target,
    pub pos: SourcePos,
}

pub(crate) struct RawNode {
    pub tag: String,
    pub plugin: String,
    pub id: Option<String>,
    pub pos: SourcePos,
    /// `version` of the file the node comes from (< 2.0.0 triggers the v1 upgrade).
    pub version: [u32; 3],
    pub properties: Properties,
    pub children: Vec<RawChild>,
}

/// All object nodes (index 0 is the root `<scene>`) and the id → node map, aliases included.
#[derive(Default)]
pub(crate) struct RawScene {
    pub nodes: Vec<RawNode>,
    pub ids: HashMap<String, (usize, SourcePos)>,
    /// Folders added by `<path>`, most recent first.
    pub search_paths: Vec<std::path::PathBuf>,
}

impl RawScene {
    /// Where `name` is already used in node `parent` (as a property or a named child).
    fn name_taken(&self, parent: usize, name: &str) -> Option<&SourcePos> {
        let n = &self.nodes[parent];
        if let Some(p) = n.properties.iter().find(|p| p.name == name) {
            return Some(&p.pos);
        }
        n.children.iter().find(|c| c.name.as_deref() == Some(name)).map(|c| &c.pos)
    }

    fn duplicate(&self, parent: usize, name: &str, pos: &SourcePos) -> Result<(), SceneError> {
        match self.name_taken(parent, name) {
            None => Ok(()),
            Some(first) => Err(SceneError::at(
                pos,
                format!("\"{name}\" is specified more than once in <{}> (first at {first})", self.nodes[parent].tag),
            )),
        }
    }

    /// Adds a property to `parent`; a name already used there is an error (Mitsuba: "Property
    /// ... was specified multiple times").
    pub(crate) fn add_property(&mut self, parent: usize, p: Property) -> Result<(), SceneError> {
        self.duplicate(parent, &p.name, &p.pos)?;
        self.nodes[parent].properties.push(p);
        Ok(())
    }

    /// Adds a nested object or `<ref>` to `parent`; a `name` already used there is an error.
    /// (Mitsuba silently lets a later nested object replace an earlier one of the same name;
    /// matte refuses rather than guess which one was meant.)
    pub(crate) fn add_child(&mut self, parent: usize, c: RawChild) -> Result<(), SceneError> {
        if let Some(name) = &c.name {
            self.duplicate(parent, name, &c.pos)?;
        }
        self.nodes[parent].children.push(c);
        Ok(())
    }

    /// Registers `id` for node `index`; ids are global across includes and must be unique.
    pub(crate) fn add_id(&mut self, id: &str, index: usize, pos: &SourcePos) -> Result<(), SceneError> {
        if let Some((_, first)) = self.ids.get(id) {
            return Err(SceneError::at(pos, format!("duplicate id \"{id}\" (first at {first})")));
        }
        self.ids.insert(id.to_string(), (index, pos.clone()));
        Ok(())
    }
}
