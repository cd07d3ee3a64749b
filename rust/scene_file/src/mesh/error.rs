//! [`MeshError`], the one error of every mesh loader: the file, the line when known, and the
//! problem.

use std::fmt;
use std::path::{Path, PathBuf};

/// A mesh file that cannot be loaded: names the file, the line when known, and the problem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshError {
    pub path: PathBuf,
    pub line: Option<usize>,
    pub message: String,
}

impl MeshError {
    pub(crate) fn new(path: &Path, message: impl Into<String>) -> Self {
        MeshError { path: path.to_path_buf(), line: None, message: message.into() }
    }

    pub(crate) fn at(path: &Path, line: usize, message: impl Into<String>) -> Self {
        MeshError { path: path.to_path_buf(), line: Some(line), message: message.into() }
    }
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "{}:{l}: {}", self.path.display(), self.message),
            None => write!(f, "{}: {}", self.path.display(), self.message),
        }
    }
}

impl std::error::Error for MeshError {}
