//! The `matte` command line. Every subcommand prints JSON or a text table on stdout; invalid
//! input ends with a one-line error on stderr and a non-zero exit code.

pub mod bench_cmd;
mod brdf_cmd;
pub mod fit_cmd;
pub mod microgeometry_cmd;
pub mod render_cmd;
pub mod study_cmd;
mod tables;
pub mod types_cmd;
pub mod validate_cmd;

use clap::{Parser, Subcommand};

#[derive(Parser, Debug)]
#[command(
    name = "matte",
    version,
    about = "Diffuse reflection models for global illumination, checked against Mitsuba 3"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
    /// The Python that runs Mitsuba's side (validate, study, bench, fit) and holds the package
    /// data: this one, else $MATTE_PYTHON, else the Python of the `matte` command that was run
    /// (python3 beside it), else python3 on PATH; the first that can import matte_mitsuba.
    #[arg(long, global = true, value_name = "PATH")]
    pub python: Option<std::path::PathBuf>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Evaluate one BSDF at one configuration (or on a grid) and print JSON.
    Brdf(brdf_cmd::BrdfArgs),
    /// Directional albedo (white furnace, reflectance 1 unless given) as JSON.
    Albedo(brdf_cmd::AlbedoArgs),
    /// Print matte's values for the reference configurations of Tables 1-2
    /// (docs/models.md#reference-values) and the van Ginneken fast-path error.
    Tables(tables::TablesArgs),
    /// Render a Mitsuba 3 XML scene with the Rust path tracer (EXR, optional PNG).
    Render(render_cmd::RenderArgs),
    /// Render scenes with matte and the installed Mitsuba and test per pixel whether they agree
    /// (`--all`: every bundled scene, a self-test of the installation).
    Validate(validate_cmd::ValidateArgs),
    /// The seed paper's study: its scenes with every diffuse model, strips and measured ratios.
    Study(study_cmd::StudyArgs),
    /// Simulate a rough model's own microsurface (V-cavities, Gaussian height field) and compare
    /// the models with it (JSON).
    Microgeometry(microgeometry_cmd::MicrogeometryArgs),
    /// Speed against the installed Mitsuba (same scenes, same spp, one run) and the speed targets (docs/performance.md).
    Bench(bench_cmd::BenchArgs),
    /// Inverse rendering: fit scene parameters (textured σ, reflectance, …) to target images
    /// with Mitsuba's prb and Adam (runs `python -m matte_mitsuba.fit`).
    Fit(fit_cmd::FitArgs),
    /// The diffuse models matte provides: plugin names one per line (the plugin build reads
    /// them), `--json` (parameters, defaults, ranges, examples) or `--markdown` (the README table).
    Types(types_cmd::TypesArgs),
}

/// Parses the command line; usage errors become one line (clap's own multi-line report is
/// kept for `--help` and `--version`).
pub fn parse() -> Result<Cli, String> {
    Cli::try_parse().map_err(|e| {
        use clap::error::ErrorKind;
        if matches!(
            e.kind(),
            ErrorKind::DisplayHelp | ErrorKind::DisplayVersion | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
        ) {
            e.exit();
        }
        let text = e.to_string();
        text.lines().next().unwrap_or("invalid arguments").trim_start_matches("error: ").to_string()
    })
}

/// An error message as the one line `matte` prints: control characters (a line break quoted
/// from a malformed file, a tab) are written escaped, as `\n` or `\u{1b}`, so the message
/// never spans lines and never drives the terminal.
pub fn one_line(message: &str) -> String {
    message.chars().map(|c| if c.is_control() { c.escape_default().to_string() } else { c.to_string() }).collect()
}

pub fn run(cli: Cli) -> Result<(), String> {
    crate::installation::set_python_flag(cli.python);
    // Scenes name packaged data (`ground_truth/<table>.json`) as Mitsuba's file resolver finds it.
    matte_render::load::set_package_folder(|| crate::installation::package_dir().ok());
    match cli.command {
        Command::Brdf(a) => brdf_cmd::run_brdf(&a),
        Command::Albedo(a) => brdf_cmd::run_albedo(&a),
        Command::Tables(a) => tables::run(&a),
        Command::Render(a) => render_cmd::run(&a),
        Command::Validate(a) => validate_cmd::run(&a),
        Command::Study(a) => study_cmd::run(&a),
        Command::Bench(a) => bench_cmd::run(&a),
        Command::Microgeometry(a) => microgeometry_cmd::run(&a),
        Command::Fit(a) => fit_cmd::run(&a),
        Command::Types(a) => types_cmd::run(&a),
    }
}
