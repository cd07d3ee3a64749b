//! Mitsuba 3 XML → a generic object tree with typed properties (docs/renderer-semantics.md §1–3;
//! Mitsuba's `src/core/parser.cpp`, `src/core/properties.cpp`). This layer knows the file
//! format, not the plugins: the scene builder walks the tree, queries what each plugin
//! reads, and finally calls [`SceneObject::check_all_used`] (or [`SceneObject::check_tree_used`])
//! so that anything it did not understand is an error, as in Mitsuba.
//!
//! # API
//! ```text
//! parse_file(path, overrides) / parse_str(xml, path, overrides) -> Result<Rc<SceneObject>, SceneError>
//!
//! SceneObject { tag, plugin ("" for <scene>), id, pos, properties: Properties, children: Vec<Child> }
//!   .child(name) -> Option<&Child>                  by `name` attribute; marks it used
//!   .children_with_tag(tag) -> impl Iterator<&Child> marks each yielded child used
//!   .check_all_used()                                first unqueried property, then unused child
//!   .check_tree_used()                               the same over everything reachable
//! Child { name: Option<String>, object: Rc<SceneObject>, pos, used: Cell<bool> }  .mark_used()
//!
//! Properties (document order, unique names)
//!   .float .integer .boolean .string .point .vector .transform (name) -> Result<Option<T>>
//!   .color(name, ColorUse) -> Result<Option<[f64; 3]>>
//!   .contains(name) (does not mark) .get(name) (marks) .iter() .len() .is_empty()
//!   .check_all_used(tag, plugin)
//! Property { name, value: Value, pos, used: Cell<bool> }
//! Value { Integer(i64), Float(f64), Boolean, String, Rgb([f64; 3]), Spectrum(Spectrum),
//!         Point(DVec3), Vector(DVec3), Transform(DMat4) }      .type_name()
//! Spectrum { Constant(f64), Sampled(Vec<(λ nm, value)>) }
//! ColorUse { Bounded, Unbounded, Emissive }
//! spectrum_list_to_srgb(samples, bounded, d65) -> [f64; 3]     (also for conductor presets, §10)
//! transform::{rotate, look_at, coordinate_system}              the §3 matrices
//! ```
//!
//! # Conversions (Mitsuba's)
//! * `float()` accepts an integer, `integer()` never a float; `point()` and `vector()`
//!   accept each other (one 3-vector type in Mitsuba 3); booleans are `true`/`false` in any case.
//! * Getters mark the property used even when they return a type error.
//! * Numbers are f64, parsed like Mitsuba (`inf`/`nan` are accepted in plain floats as there;
//!   any NaN/∞ inside a `<transform>` is an error).
//!
//! # Where matte is stricter than Mitsuba 3.9.1
//! * A name given twice in one object is always an error (Mitsuba lets a later nested object
//!   silently replace an earlier one of the same name).
//! * A property or `<ref>` directly inside an included `<scene>` is an error (Mitsuba drops it).
//! * A transform containing NaN or ∞ is an error (Mitsuba only checks `lookat`).
//! * `<path value>` folders of the main file end up in the root's `search_paths` (for the
//!   scene's assets); `<spectrum filename=...>` files are read at parse time through the
//!   resolver of the moment, as Mitsuba does.
//! * The root element must be `<scene>`; it takes only `version`.
//!
//! # For the builder
//! * `pos.file` of an object from an included file is that file, but Mitsuba resolves asset
//!   file names (`obj`/`ply`/`bitmap` `filename`) against the MAIN scene's folder, not the
//!   including one (docs/renderer-semantics.md §1 pitfall).
//! * Unnamed children have `name: None` (Mitsuba's `_arg_N`).
//!
//! Not reproduced because it does not change the image: merging of identical nodes and the
//! wrapping of top-level shapes into a `merge` shape.

mod attrs;
mod cie;
mod color;
mod numbers;
mod object;
mod parse;
mod properties;
mod property_values;
mod raw;
mod resolve;
mod substitute;
pub mod transform;
mod upgrade;

use std::path::Path;
use std::rc::Rc;

pub use color::{ColorUse, spectrum_list_to_srgb};
pub use object::{Child, SceneObject};
pub use properties::{Properties, Property, Spectrum, Value};

use crate::error::{SceneError, SourcePos};

/// Reads and parses the scene file at `path`. `overrides` are `-D name=value` pairs; each
/// must be used by some `$name`, and they beat `<default>`s.
pub fn parse_file(path: &Path, overrides: &[(String, String)]) -> Result<Rc<SceneObject>, SceneError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| SceneError::at(&SourcePos::file_only(path), format!("cannot read scene file: {e}")))?;
    parse_str(&text, path, overrides)
}

/// Parses scene XML given as a string; `path` names it in messages and is the base for
/// relative `<include>` file names.
pub fn parse_str(xml: &str, path: &Path, overrides: &[(String, String)]) -> Result<Rc<SceneObject>, SceneError> {
    let mut p = parse::Parser::new(overrides);
    p.parse_main(xml, path)?;
    p.params.check_all_used(&SourcePos::file_only(path))?;
    let mut scene = p.scene;
    for node in &mut scene.nodes {
        upgrade::upgrade_v1(node)?;
    }
    resolve::build_tree(scene)
}
