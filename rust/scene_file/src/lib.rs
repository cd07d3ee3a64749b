//! Mitsuba 3 scene files: the XML → a typed description the renderer builds from, and the mesh
//! files it references. Parsing keeps source positions so every error names file, line and
//! element (`docs/renderer-semantics.md` §1–3 and §8 list the semantics matched here).

pub mod error;
pub mod mesh;
pub mod xml;

pub use error::{SceneError, SourcePos};
