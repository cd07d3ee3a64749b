//! `matte fit`: inverse rendering with matte's models. The optimisation runs in Mitsuba 3
//! (its `prb` integrator and `mi.ad.Adam`, through matte's plugins), so this subcommand only
//! forwards its arguments to `python -m matte_mitsuba.fit` (`python/matte_mitsuba/fit.py`,
//! which documents them) in the Python environment matte is installed in
//! ([`crate::installation`]). The wheel's own `matte` command runs the same module in-process.

use clap::Args;

#[derive(Args, Debug)]
pub struct FitArgs {
    /// Arguments of `python -m matte_mitsuba.fit` (`matte fit -- --help` lists them).
    #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
    pub args: Vec<String>,
}

pub fn run(a: &FitArgs) -> Result<(), String> {
    let python = crate::installation::mitsuba_side()?;
    let status = python
        .module("fit")
        .args(&a.args)
        .status()
        .map_err(|e| format!("cannot start {} for matte fit: {e}", python.python.display()))?;
    match status.code() {
        Some(0) => Ok(()),
        // The fit printed its own one-line error; keep its exit status.
        Some(code) => std::process::exit(code),
        None => Err("matte fit: the Python process was killed by a signal".into()),
    }
}
