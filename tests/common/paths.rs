//! Where the tests find the repository and Mitsuba: shared by every integration test crate
//! (std only, so that a crate's tests link nothing but that crate).

use std::path::{Path, PathBuf};

/// The repository's top folder (the workspace root, which holds `Cargo.lock`), whichever
/// crate's test this is.
pub fn repo() -> PathBuf {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    crate_dir.ancestors().find(|d| d.join("Cargo.lock").exists()).unwrap_or(crate_dir).to_path_buf()
}

/// The project's `.venv` Python (Mitsuba 3.9.1, as `make venv` installs it), if this checkout
/// has one; checks against Mitsuba itself are skipped (with a note) where it does not. `make
/// test` builds the venv first, so the suite always runs them. A venv keeps it in `bin/python`,
/// on Windows in `Scripts\python.exe`.
pub fn mitsuba_python() -> Option<std::path::PathBuf> {
    let venv = repo().join(".venv");
    let python = if cfg!(windows) { venv.join("Scripts").join("python.exe") } else { venv.join("bin/python") };
    if python.exists() {
        Some(python)
    } else {
        println!("note: {} not found; skipping a check against Mitsuba itself", python.display());
        None
    }
}
