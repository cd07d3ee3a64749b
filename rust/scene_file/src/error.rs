//! Errors while reading a scene: every message names the file and, where known, the line and
//! column of the XML element (or mesh line) at fault. Users would rather know than get a
//! silently different picture, so anything matte does not understand is one of these.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A position in a source file (1-based line and column).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourcePos {
    pub file: Arc<PathBuf>,
    pub line: u32,
    pub col: u32,
}

impl SourcePos {
    pub fn new(file: Arc<PathBuf>, line: u32, col: u32) -> Self {
        SourcePos { file, line, col }
    }

    /// A position naming a whole file (no line known).
    pub fn file_only(file: &Path) -> Self {
        SourcePos { file: Arc::new(file.to_path_buf()), line: 0, col: 0 }
    }
}

impl fmt::Display for SourcePos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.line, self.col) {
            (0, _) => write!(f, "{}", self.file.display()),
            (l, 0) => write!(f, "{}:{l}", self.file.display()),
            (l, c) => write!(f, "{}:{l}:{c}", self.file.display()),
        }
    }
}

/// A scene that cannot be loaded or rendered as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    pub pos: Option<SourcePos>,
    pub message: String,
}

impl SceneError {
    pub fn at(pos: &SourcePos, message: impl Into<String>) -> Self {
        SceneError { pos: Some(pos.clone()), message: message.into() }
    }

    pub fn new(message: impl Into<String>) -> Self {
        SceneError { pos: None, message: message.into() }
    }
}

impl fmt::Display for SceneError {
    /// One line: control characters in the message (a newline quoted from the file, say) are
    /// written escaped.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(p) = &self.pos {
            write!(f, "{p}: ")?;
        }
        for c in self.message.chars() {
            if c.is_control() {
                write!(f, "{}", c.escape_default())?;
            } else {
                fmt::Write::write_char(f, c)?;
            }
        }
        Ok(())
    }
}

impl std::error::Error for SceneError {}
