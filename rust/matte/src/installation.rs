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
//! Those are the names on Linux, macOS and the other Unix systems. On Windows ([`Platform`])
//! the interpreter is `python.exe`, beside `matte.exe` and on `PATH`, and an environment laid
//! out as `<prefix>\Lib\site-packages\matte_mitsuba\bin\matte.exe` has it as
//! `<prefix>\Scripts\python.exe` (a venv) or `<prefix>\python.exe` (an installation, a conda
//! environment).
//!
//! An explicit choice (1, 2) is used as given, and is an error when it cannot import
//! `matte_mitsuba`; the others are candidates, skipped when they cannot. When none works, the
//! error is one line naming what was tried and how to fix it.
//!
//! The package folder is the one the binary ships in when it does (the installed wheel),
//! else the `matte_mitsuba` folder of the Python side (a checkout's `target/release/matte`
//! with `--python .venv/bin/python`). Nothing is looked up in the tree the binary was built
//! from.

use std::ffi::OsStr;
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
    let binary = canonical(binary, Platform::HOST)?;
    let package = binary.parent()?.parent()?;
    (package.file_name()? == "matte_mitsuba" && package.join("__init__.py").is_file()).then(|| package.to_path_buf())
}

/// `<prefix>` when `binary` is `<prefix>/lib/pythonX.Y/{site,dist}-packages/matte_mitsuba/bin/matte`
/// (on Windows `<prefix>\Lib\site-packages\matte_mitsuba\bin\matte.exe`), with the layout
/// of `platform`.
fn installed_prefix_on(binary: &Path, platform: Platform) -> Option<PathBuf> {
    platform.prefix_of_packages(package_of_binary(binary)?.parent()?)
}

/// `path` made absolute with every link resolved, in the form the platform's other calls take
/// ([`Platform::plain_path`]).
fn canonical(path: &Path, platform: Platform) -> Option<PathBuf> {
    path.canonicalize().ok().map(|p| platform.plain_path(p))
}

/// The conventions of a platform that the rule depends on: the interpreter's file name and
/// where an environment keeps it and its packages. The program follows [`Platform::HOST`];
/// the tests name each platform, so that every platform's rule is checked on any.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Platform {
    /// Linux, macOS and the other Unix systems: `python3`; an environment at `<prefix>` has
    /// `<prefix>/bin/python3` and its packages in `<prefix>/lib/pythonX.Y/site-packages`
    /// (Debian's system Python: `dist-packages`; some systems: `lib64`).
    Unix,
    /// Windows: `python.exe`; an environment at `<prefix>` has its packages in
    /// `<prefix>\Lib\site-packages` and its interpreter in `<prefix>\Scripts` (a venv) or
    /// `<prefix>` itself (an installation, a conda environment).
    Windows,
}

impl Platform {
    /// The platform this program was built for.
    pub const HOST: Platform = if cfg!(windows) { Platform::Windows } else { Platform::Unix };

    /// The interpreter's file name, as looked for beside `matte` and on `PATH`.
    pub fn python(self) -> &'static str {
        match self {
            Platform::Unix => "python3",
            Platform::Windows => "python.exe",
        }
    }

    /// The interpreters of the environment at `prefix`, in the order they are tried.
    pub fn environment_pythons(self, prefix: &Path) -> Vec<PathBuf> {
        match self {
            Platform::Unix => vec![prefix.join("bin").join("python3")],
            Platform::Windows => vec![prefix.join("Scripts").join("python.exe"), prefix.join("python.exe")],
        }
    }

    /// `<prefix>` when `packages` is the packages folder of an environment at `<prefix>`
    /// (folder names only; Windows's are compared without case, as its file system does).
    pub fn prefix_of_packages(self, packages: &Path) -> Option<PathBuf> {
        let named = |p: &Path, ok: &dyn Fn(&str) -> bool| p.file_name().and_then(|n| n.to_str()).is_some_and(ok);
        let lib = match self {
            Platform::Unix => {
                let python = packages.parent()?;
                let lib = python.parent()?;
                let laid_out = named(packages, &|n| n == "site-packages" || n == "dist-packages")
                    && named(python, &|n| n.starts_with("python"))
                    && named(lib, &|n| n == "lib" || n == "lib64");
                laid_out.then_some(lib)?
            }
            Platform::Windows => {
                let lib = packages.parent()?;
                let laid_out = named(packages, &|n| n.eq_ignore_ascii_case("site-packages"))
                    && named(lib, &|n| n.eq_ignore_ascii_case("lib"));
                laid_out.then_some(lib)?
            }
        };
        lib.parent().map(Path::to_path_buf)
    }

    /// The file that a command runs as `command` (its first argument): as given on Unix; on
    /// Windows with `.exe` when it has no extension (`matte` runs `matte.exe`).
    pub fn executable(self, command: &Path) -> PathBuf {
        match self {
            Platform::Windows if command.extension().is_none() => command.with_extension("exe"),
            _ => command.to_path_buf(),
        }
    }

    /// `path` (a canonical path) in the form that other paths can be joined to. On Windows,
    /// `canonicalize` gives a verbatim path (`\\?\C:\…`, `\\?\UNC\server\share\…`), in
    /// which `/` is no separator, so that a scene's `meshes/bunny.ply` joined to it would name
    /// no file: the prefix is dropped where the plain path names the same file (shorter than
    /// 260 characters, no component that Windows would rewrite: a trailing dot or space, a
    /// device name such as `NUL`). On Unix, and for any other path, `path` as it is.
    pub fn plain_path(self, path: PathBuf) -> PathBuf {
        if self != Platform::Windows {
            return path;
        }
        let Some(text) = path.to_str() else { return path };
        let plain = if let Some(rest) = text.strip_prefix(r"\\?\UNC\") {
            format!(r"\\{rest}")
        } else if let Some(rest) = text.strip_prefix(r"\\?\")
            && let [drive, b':', b'\\', ..] = rest.as_bytes()
            && drive.is_ascii_alphabetic()
        {
            rest.to_string()
        } else {
            return path;
        };
        let keeps_its_meaning = |c: &str| {
            let stem = c.split('.').next().unwrap_or(c).trim_end();
            let device = ["CON", "PRN", "AUX", "NUL"].iter().any(|d| stem.eq_ignore_ascii_case(d))
                || ["COM", "LPT"].iter().any(|d| {
                    stem.len() == 4
                        && stem.is_char_boundary(3)
                        && stem[..3].eq_ignore_ascii_case(d)
                        && stem.as_bytes()[3].is_ascii_digit()
                });
            !c.ends_with(['.', ' ']) && !c.contains('/') && !device
        };
        if plain.len() < 260 && plain.split('\\').skip(1).all(keeps_its_meaning) { PathBuf::from(plain) } else { path }
    }
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
    /// This executable ([`std::env::current_exe`]).
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
            .map(|a| Platform::HOST.executable(Path::new(&a)))
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
fn on_path(path: Option<&OsStr>, name: &OsStr) -> Option<PathBuf> {
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
    let mut tried = Vec::new();
    for (python, how) in candidates(env, Platform::HOST) {
        if !python.is_file() {
            continue;
        }
        match probe(&python, &how) {
            Ok(side) => return Ok(side),
            Err(e) => tried.push(format!("{} ({how}): {e}", python.display())),
        }
    }
    let tried = if tried.is_empty() {
        format!("no --python, no MATTE_PYTHON, no {} beside matte or on PATH", Platform::HOST.python())
    } else {
        format!("no --python, no MATTE_PYTHON; tried {}", tried.join("; "))
    };
    Err(format!(
        "no Python with matte_mitsuba found ({tried}); install matte-mitsuba into a Python environment (pip install \
         matte-mitsuba) and run its matte, or name the interpreter with --python PATH or MATTE_PYTHON"
    ))
}

/// The interpreters that step 3 and 4 of the rule try, in order, each with how it was found
/// (the files need not exist) on `platform`.
fn candidates(env: &Environment, platform: Platform) -> Vec<(PathBuf, String)> {
    let python = platform.python();
    let mut candidates: Vec<(PathBuf, String)> = Vec::new();
    if let Some(p) = &env.launcher_python {
        candidates.push((p.clone(), "the matte command's Python".into()));
    }
    if let Some(matte) = &env.invoked_as {
        // Beside the `matte` that was run, and beside the file a symlink to it points at (pipx).
        let mut dirs: Vec<PathBuf> = matte.parent().map(Path::to_path_buf).into_iter().collect();
        if let Some(d) = canonical(matte, platform).and_then(|r| r.parent().map(Path::to_path_buf))
            && !dirs.contains(&d)
        {
            dirs.push(d);
        }
        for d in dirs {
            candidates.push((d.join(python), "beside the matte executable".into()));
        }
    }
    if let Some(prefix) = env.executable.as_deref().and_then(|e| installed_prefix_on(e, platform)) {
        for p in platform.environment_pythons(&prefix) {
            candidates.push((p, "the environment matte is installed in".into()));
        }
    }
    if let Some(p) = on_path(env.path.as_deref(), python.as_ref()) {
        candidates.push((p, format!("{python} on PATH")));
    }
    candidates
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
        let root = canonical(&root, Platform::HOST).unwrap();
        let package = root.join("lib/python3.11/site-packages/matte_mitsuba");
        assert_eq!(package_of_binary(&binary), Some(package.clone()));
        assert_eq!(installed_prefix_on(&binary, Platform::Unix), Some(root.clone()));
        // Not a package: no `__init__.py`, or another folder name.
        std::fs::remove_file(package.join("__init__.py")).unwrap();
        assert_eq!(package_of_binary(&binary), None);
        assert_eq!(installed_prefix_on(&binary, Platform::Unix), None);
        let _ = std::fs::remove_dir_all(&root);
    }

    #[test]
    fn with_nothing_to_try_the_error_names_every_step_and_the_fix() {
        let e = find_python_side(None, &Environment::default()).unwrap_err();
        let start =
            format!("no Python with matte_mitsuba found (no --python, no MATTE_PYTHON, no {}", Platform::HOST.python());
        assert!(e.starts_with(&start), "{e}");
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

    /// Each platform's names and layouts, checked on any platform.
    #[test]
    fn each_platform_names_its_interpreter_and_where_an_environment_keeps_it() {
        assert_eq!(Platform::Unix.python(), "python3");
        assert_eq!(Platform::Windows.python(), "python.exe");
        assert_eq!(Platform::HOST, if cfg!(windows) { Platform::Windows } else { Platform::Unix });
        let prefix = Path::new("env");
        assert_eq!(Platform::Unix.environment_pythons(prefix), [prefix.join("bin").join("python3")]);
        assert_eq!(
            Platform::Windows.environment_pythons(prefix),
            [prefix.join("Scripts").join("python.exe"), prefix.join("python.exe")]
        );
        // `matte` runs `matte.exe` on Windows; a name with an extension, and any name on Unix, as given.
        assert_eq!(Platform::Windows.executable(Path::new("matte")), Path::new("matte.exe"));
        assert_eq!(Platform::Windows.executable(&Path::new("bin").join("matte")), Path::new("bin").join("matte.exe"));
        assert_eq!(Platform::Windows.executable(Path::new("matte.exe")), Path::new("matte.exe"));
        assert_eq!(Platform::Unix.executable(Path::new("matte")), Path::new("matte"));
    }

    #[test]
    fn an_environments_prefix_is_found_from_its_packages_folder_by_each_platforms_layout() {
        let at = |parts: &[&str]| parts.iter().fold(PathBuf::from("root"), |p, c| p.join(c));
        let unix = at(&["env", "lib", "python3.11", "site-packages"]);
        let windows = at(&["env", "Lib", "site-packages"]);
        assert_eq!(Platform::Unix.prefix_of_packages(&unix), Some(at(&["env"])));
        assert_eq!(
            Platform::Unix.prefix_of_packages(&at(&["env", "lib64", "python3.12", "dist-packages"])),
            Some(at(&["env"]))
        );
        assert_eq!(Platform::Unix.prefix_of_packages(&windows), None);
        assert_eq!(Platform::Unix.prefix_of_packages(&at(&["env", "share", "python3.11", "site-packages"])), None);
        assert_eq!(Platform::Windows.prefix_of_packages(&windows), Some(at(&["env"])));
        assert_eq!(Platform::Windows.prefix_of_packages(&at(&["env", "lib", "Site-Packages"])), Some(at(&["env"])));
        assert_eq!(Platform::Windows.prefix_of_packages(&unix), None);
        assert_eq!(Platform::Windows.prefix_of_packages(&at(&["env", "Lib", "packages"])), None);
    }

    #[test]
    fn a_verbatim_windows_path_is_made_plain_only_where_it_names_the_same_file() {
        let plain = |p: &str| Platform::Windows.plain_path(PathBuf::from(p));
        assert_eq!(
            plain(r"\\?\C:\Users\me\venv\Lib\site-packages\matte_mitsuba"),
            Path::new(r"C:\Users\me\venv\Lib\site-packages\matte_mitsuba")
        );
        assert_eq!(plain(r"\\?\UNC\server\share\venv\Scripts"), Path::new(r"\\server\share\venv\Scripts"));
        // Already plain, or not a drive path: as it is.
        assert_eq!(plain(r"C:\venv"), Path::new(r"C:\venv"));
        assert_eq!(plain(r"\\?\Volume{0a1b}\venv"), Path::new(r"\\?\Volume{0a1b}\venv"));
        // Names that Windows would read otherwise without the prefix keep it.
        for kept in [r"\\?\C:\venv\NUL", r"\\?\C:\venv\com1.txt", r"\\?\C:\venv\dir.", r"\\?\C:\venv\dir \x"] {
            assert_eq!(plain(kept), Path::new(kept));
        }
        let long = format!(r"\\?\C:\{}", "d\\".repeat(200));
        assert_eq!(plain(&long), Path::new(&long));
        assert_eq!(plain(r"\\?\C:\venv\console\auxiliary"), Path::new(r"C:\venv\console\auxiliary"));
        // Unix paths are never rewritten.
        assert_eq!(Platform::Unix.plain_path(PathBuf::from(r"\\?\C:\venv")), Path::new(r"\\?\C:\venv"));
        assert_eq!(Platform::Unix.plain_path(PathBuf::from("/usr/bin")), Path::new("/usr/bin"));
    }

    /// The candidates of steps 3 and 4 for a binary installed in an environment of each
    /// platform's layout, made in a temporary folder (of whichever platform runs the test).
    #[test]
    fn the_candidates_are_each_platforms_interpreters_of_the_environment_matte_is_in() {
        let root = std::env::temp_dir().join(format!("matte_candidates_{}", std::process::id()));
        for (platform, packages, binary, on_path) in [
            (Platform::Unix, &["unix", "lib", "python3.11", "site-packages"][..], "matte", "python3"),
            (Platform::Windows, &["windows", "Lib", "site-packages"][..], "matte.exe", "python.exe"),
        ] {
            let env_dir = root.join(packages[0]);
            let package = packages[1..].iter().fold(env_dir.clone(), |p, c| p.join(c)).join("matte_mitsuba");
            std::fs::create_dir_all(package.join("bin")).unwrap();
            std::fs::write(package.join("__init__.py"), "").unwrap();
            let matte = package.join("bin").join(binary);
            std::fs::write(&matte, "").unwrap();
            let path_dir = root.join(format!("{}_path", packages[0]));
            std::fs::create_dir_all(&path_dir).unwrap();
            std::fs::write(path_dir.join(on_path), "").unwrap();

            let env = Environment {
                launcher_python: Some(PathBuf::from("launcher")),
                invoked_as: Some(matte.clone()),
                executable: Some(matte.clone()),
                path: Some(std::env::join_paths([&path_dir]).unwrap()),
                ..Default::default()
            };
            let prefix = canonical(&env_dir, Platform::HOST).unwrap();
            let bin_dir = canonical(&package.join("bin"), Platform::HOST).unwrap();
            let mut expected = vec![
                (PathBuf::from("launcher"), "the matte command's Python".to_string()),
                (package.join("bin").join(platform.python()), "beside the matte executable".into()),
            ];
            if bin_dir != package.join("bin") {
                expected.push((bin_dir.join(platform.python()), "beside the matte executable".into()));
            }
            for p in platform.environment_pythons(&prefix) {
                expected.push((p, "the environment matte is installed in".into()));
            }
            expected.push((path_dir.join(on_path), format!("{on_path} on PATH")));
            assert_eq!(candidates(&env, platform), expected, "{platform:?}");
        }
        let _ = std::fs::remove_dir_all(&root);
    }
}
