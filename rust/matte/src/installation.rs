//! Where the parts of matte that the `matte` binary does not hold are found at run time. The
//! binary ships inside the `matte_mitsuba` Python package (`<package>/bin/matte`, the wheel's
//! `matte` command runs it), and two things come from that installation:
//!
//! * **the Python side**: the interpreter of an environment where `matte_mitsuba` (and so
//!   Mitsuba) is installed, which runs every command's Mitsuba side as
//!   `python -m matte_mitsuba.<module>` (validate's passes, the study's Mitsuba renderer and
//!   convergence series, bench, fit);
//! * **the package data**: the bundled scenes (`<package>/scenes`), the simulated surfaces'
//!   tables (`<package>/ground_truth`) and the study report's BRDF slices
//!   (`<package>/truth_slices`).
//!
//! The interpreter is the first of these that applies (the one rule; `matte --help` and the
//! README state it):
//! 1. `--python PATH` (every command takes it);
//! 2. the environment variable `MATTE_PYTHON`;
//! 3. the Python of the environment this `matte` belongs to: the one that runs the wheel's
//!    `matte` command (its launcher passes `sys.executable` as `MATTE_LAUNCHER_PYTHON`),
//!    `python3` beside the `matte` that was run, and `<prefix>/bin/python3` for a binary
//!    installed as `<prefix>/lib/pythonX.Y/site-packages/matte_mitsuba/bin/matte`;
//! 4. `python3` on `PATH`.
//!
//! An explicit choice (1, 2) is used as given, and is an error when it cannot import
//! `matte_mitsuba`; the others are candidates, skipped when they cannot. When none works, the
//! error is one line naming what was tried and how to fix it.
//!
//! The package folder is the one the binary ships in when it does (the installed wheel),
//! else the `matte_mitsuba` folder of the Python side (a checkout's `target/release/matte`
//! with `--python .venv/bin/python`). Nothing is looked up in the tree the binary was built
//! from.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Mutex, OnceLock};

/// The Python environment with `matte_mitsuba` that runs Mitsuba's side.
#[derive(Clone, Debug)]
pub struct PythonSide {
    /// The interpreter.
    pub python: PathBuf,
    /// How it was chosen ("--python", "MATTE_PYTHON", "the matte command's Python", …).
    pub chosen_by: String,
    /// The folder of its `matte_mitsuba` package.
    pub package: PathBuf,
    /// The installed Mitsuba's version (`None`: Mitsuba is not installed there).
    pub mitsuba: Option<String>,
}

impl PythonSide {
    /// `python -m matte_mitsuba.<module>` in this environment.
    pub fn module(&self, module: &str) -> Command {
        let mut cmd = Command::new(&self.python);
        cmd.arg("-m").arg(format!("matte_mitsuba.{module}"));
        cmd
    }

    /// One line for reports: interpreter, how it was chosen, Mitsuba's version.
    pub fn describe(&self) -> String {
        format!(
            "{} ({}), Mitsuba {}, matte_mitsuba in {}",
            self.python.display(),
            self.chosen_by,
            self.mitsuba.as_deref().unwrap_or("not installed"),
            self.package.display()
        )
    }
}

/// The interpreter named by `--python` (set once by the command line before any lookup).
static PYTHON_FLAG: Mutex<Option<PathBuf>> = Mutex::new(None);
static PYTHON_SIDE: OnceLock<Result<PythonSide, String>> = OnceLock::new();
static PACKAGE: OnceLock<Result<PathBuf, String>> = OnceLock::new();

/// Sets the interpreter given with `--python` (before the first [`python_side`]).
pub fn set_python_flag(python: Option<PathBuf>) {
    *PYTHON_FLAG.lock().unwrap_or_else(|e| e.into_inner()) = python;
}

/// The Python side, found by the rule of this module (once per process).
pub fn python_side() -> Result<PythonSide, String> {
    PYTHON_SIDE
        .get_or_init(|| {
            let flag = PYTHON_FLAG.lock().unwrap_or_else(|e| e.into_inner()).clone();
            find_python_side(flag.as_deref(), &Environment::of_process())
        })
        .clone()
}

/// The Python side, when Mitsuba is installed there (what runs Mitsuba's side of a command);
/// otherwise an error saying which environment lacks it.
pub fn mitsuba_side() -> Result<PythonSide, String> {
    let side = python_side()?;
    if side.mitsuba.is_none() {
        return Err(format!(
            "{} ({}) has matte_mitsuba but no Mitsuba: install it there (pip install matte-mitsuba pulls it)",
            side.python.display(),
            side.chosen_by
        ));
    }
    Ok(side)
}

/// The `matte_mitsuba` package folder that holds the data: the one this binary ships in, else
/// the Python side's (once per process).
pub fn package_dir() -> Result<PathBuf, String> {
    PACKAGE
        .get_or_init(|| match std::env::current_exe().ok().as_deref().and_then(package_of_binary) {
            Some(p) => Ok(p),
            None => python_side()
                .map(|s| s.package)
                .map_err(|e| format!("matte's package data (scenes, tables) comes with matte_mitsuba: {e}")),
        })
        .clone()
}

/// The bundled scenes: `<package>/scenes`.
pub fn scenes_dir() -> Result<PathBuf, String> {
    package_data("scenes")
}

/// The packaged folder `<package>/<name>` (for example `truth_slices`).
pub fn package_data(name: &str) -> Result<PathBuf, String> {
    let dir = package_dir()?.join(name);
    if dir.is_dir() {
        Ok(dir)
    } else {
        Err(format!(
            "{} is missing: the matte_mitsuba installation is incomplete (reinstall matte-mitsuba)",
            dir.display()
        ))
    }
}

/// The scene arguments of a command: each existing file as given; a bare name that is no file
/// (`cornell`, `sphere_eon.xml`) names a bundled scene in `<scenes>/<folder>` (`folder` empty:
/// `<scenes>`) when there is one.
pub fn scene_arguments(args: &[PathBuf], folder: &str) -> Vec<PathBuf> {
    args.iter()
        .map(|a| {
            if a.exists() || a.components().count() != 1 {
                return a.clone();
            }
            let mut name = a.clone();
            if name.extension().is_none() {
                name.set_extension("xml");
            }
            // Without an installation the name stays a file name, which the load then reports.
            let in_folder = |d: PathBuf| if folder.is_empty() { d.join(&name) } else { d.join(folder).join(&name) };
            let bundled = scenes_dir().ok().map(in_folder).filter(|p| p.is_file());
            bundled.unwrap_or_else(|| a.clone())
        })
        .collect()
}

/// `<package>` when `binary` is `<package>/bin/matte` inside a `matte_mitsuba` package.
pub fn package_of_binary(binary: &Path) -> Option<PathBuf> {
    let binary = binary.canonicalize().ok()?;
    let package = binary.parent()?.parent()?;
    (package.file_name()? == "matte_mitsuba" && package.join("__init__.py").is_file()).then(|| package.to_path_buf())
}

/// `<prefix>` when `binary` is `<prefix>/lib/pythonX.Y/{site,dist}-packages/matte_mitsuba/bin/matte`.
fn installed_prefix(binary: &Path) -> Option<PathBuf> {
    let package = package_of_binary(binary)?;
    let packages = package.parent()?;
    let python = packages.parent()?;
    let lib = python.parent()?;
    let named = |p: &Path, ok: &dyn Fn(&str) -> bool| p.file_name().and_then(|n| n.to_str()).is_some_and(ok);
    let laid_out = named(packages, &|n| n == "site-packages" || n == "dist-packages")
        && named(python, &|n| n.starts_with("python"))
        && named(lib, &|n| n == "lib" || n == "lib64");
    laid_out.then(|| lib.parent().map(Path::to_path_buf)).flatten()
}

/// What the rule reads from the process: the variables and where the executable is.
#[derive(Clone, Debug, Default)]
pub struct Environment {
    /// `MATTE_PYTHON`.
    pub matte_python: Option<PathBuf>,
    /// `MATTE_LAUNCHER_PYTHON` (set by the wheel's `matte` command).
    pub launcher_python: Option<PathBuf>,
    /// The `matte` that was run (`argv[0]` found on `PATH` when it is a bare name).
    pub invoked_as: Option<PathBuf>,
    /// This executable (`/proc/self/exe`).
    pub executable: Option<PathBuf>,
    /// `PATH`.
    pub path: Option<std::ffi::OsString>,
}

impl Environment {
    pub fn of_process() -> Environment {
        let nonempty = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty()).map(PathBuf::from);
        let path = std::env::var_os("PATH");
        let invoked_as = std::env::args_os()
            .next()
            .map(PathBuf::from)
            .and_then(|a| if a.components().count() > 1 { Some(a) } else { on_path(path.as_deref(), a.as_os_str()) });
        Environment {
            matte_python: nonempty("MATTE_PYTHON"),
            launcher_python: nonempty("MATTE_LAUNCHER_PYTHON"),
            invoked_as,
            executable: std::env::current_exe().ok(),
            path,
        }
    }
}

/// The first `name` on `path` that is a file.
fn on_path(path: Option<&std::ffi::OsStr>, name: &std::ffi::OsStr) -> Option<PathBuf> {
    std::env::split_paths(path?).map(|d| d.join(name)).find(|p| p.is_file())
}

/// The rule of this module, given the `--python` flag and the environment.
pub fn find_python_side(flag: Option<&Path>, env: &Environment) -> Result<PythonSide, String> {
    if let Some(p) = flag {
        return probe(p, "--python").map_err(|e| format!("--python {}: {e}", p.display()));
    }
    if let Some(p) = &env.matte_python {
        return probe(p, "MATTE_PYTHON").map_err(|e| format!("MATTE_PYTHON={}: {e}", p.display()));
    }
    let mut candidates: Vec<(PathBuf, String)> = Vec::new();
    if let Some(p) = &env.launcher_python {
        candidates.push((p.clone(), "the matte command's Python".into()));
    }
    if let Some(matte) = &env.invoked_as {
        // Beside the `matte` that was run, and beside the file a symlink to it points at (pipx).
        let mut dirs: Vec<PathBuf> = matte.parent().map(Path::to_path_buf).into_iter().collect();
        if let Some(d) = matte.canonicalize().ok().and_then(|r| r.parent().map(Path::to_path_buf))
            && !dirs.contains(&d)
        {
            dirs.push(d);
        }
        for d in dirs {
            candidates.push((d.join("python3"), "beside the matte executable".into()));
        }
    }
    if let Some(prefix) = env.executable.as_deref().and_then(installed_prefix) {
        candidates.push((prefix.join("bin/python3"), "the environment matte is installed in".into()));
    }
    if let Some(p) = on_path(env.path.as_deref(), "python3".as_ref()) {
        candidates.push((p, "python3 on PATH".into()));
    }
    let mut tried = Vec::new();
    for (python, how) in candidates {
        if !python.is_file() {
            continue;
        }
        match probe(&python, &how) {
            Ok(side) => return Ok(side),
            Err(e) => tried.push(format!("{} ({how}): {e}", python.display())),
        }
    }
    let tried = if tried.is_empty() {
        "no --python, no MATTE_PYTHON, no python3 beside matte or on PATH".to_string()
    } else {
        format!("no --python, no MATTE_PYTHON; tried {}", tried.join("; "))
    };
    Err(format!(
        "no Python with matte_mitsuba found ({tried}); install matte-mitsuba into a Python environment (pip install \
         matte-mitsuba) and run its matte, or name the interpreter with --python PATH or MATTE_PYTHON"
    ))
}

/// What the probe prints: the package folder, then Mitsuba's version (empty line: none).
const PROBE: &str = "import importlib.util, importlib.metadata as m\n\
s = importlib.util.find_spec('matte_mitsuba')\n\
print(s.submodule_search_locations[0] if s and s.submodule_search_locations else '')\n\
try:\n    print(m.version('mitsuba'))\nexcept Exception:\n    print('')\n";

/// Runs `python` to find its `matte_mitsuba` and Mitsuba (without importing either).
fn probe(python: &Path, how: &str) -> Result<PythonSide, String> {
    let out = Command::new(python)
        .args(["-c", PROBE])
        .env_remove("PYTHONHOME")
        .output()
        .map_err(|e| format!("cannot run it: {e}"))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        let line = err.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("exited with an error");
        return Err(format!("it failed: {line}"));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let mut lines = text.lines();
    let package = lines.next().unwrap_or("").trim();
    if package.is_empty() {
        return Err("it cannot import matte_mitsuba".into());
    }
    let mitsuba = lines.next().map(str::trim).filter(|v| !v.is_empty()).map(str::to_string);
    Ok(PythonSide { python: python.to_path_buf(), chosen_by: how.into(), package: PathBuf::from(package), mitsuba })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fake installation `<root>/lib/python3.11/site-packages/matte_mitsuba/bin/matte`.
    fn fake_install(root: &Path) -> PathBuf {
        let package = root.join("lib/python3.11/site-packages/matte_mitsuba");
        std::fs::create_dir_all(package.join("bin")).unwrap();
        std::fs::write(package.join("__init__.py"), "").unwrap();
        std::fs::write(package.join("bin/matte"), "").unwrap();
        package.join("bin/matte")
    }

    #[test]
    fn a_binary_in_an_installed_package_knows_its_package_and_environment() {
        let root = std::env::temp_dir().join(format!("matte_installation_{}", std::process::id()));
        let binary = fake_install(&root);
        let root = root.canonicalize().unwrap();
        let package = root.join("lib/python3.11/site-packages/matte_mitsuba");
        assert_eq!(package_of_binary(&binary), Some(package.clone()));
        assert_eq!(installed_prefix(&binary), Some(root.clone()));
        // Not a package: no `__init__.py`, or another folder name.
        std::fs::remove_file(package.join("__init__.py")).unwrap();
        assert_eq!(package_of_binary(&binary), None);
        assert_eq!(installed_prefix(&binary), None);
        let _ = std::fs::remove_dir_all(&root);
    }

    #[test]
    fn with_nothing_to_try_the_error_names_every_step_and_the_fix() {
        let e = find_python_side(None, &Environment::default()).unwrap_err();
        assert!(e.starts_with("no Python with matte_mitsuba found (no --python, no MATTE_PYTHON, no python3"), "{e}");
        assert!(e.contains("--python PATH or MATTE_PYTHON") && !e.contains('\n'), "{e}");
    }

    #[test]
    fn explicit_choices_are_used_as_given() {
        let missing = Path::new("/nonexistent/python3");
        let env = Environment { matte_python: Some(PathBuf::from("/also/missing")), ..Default::default() };
        let e = find_python_side(Some(missing), &env).unwrap_err();
        assert!(e.starts_with("--python /nonexistent/python3: cannot run it"), "{e}");
        let e = find_python_side(None, &env).unwrap_err();
        assert!(e.starts_with("MATTE_PYTHON=/also/missing: cannot run it"), "{e}");
    }
}
