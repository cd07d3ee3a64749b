use std::process::ExitCode;

#[cfg(unix)]
unsafe extern "C" {
    fn signal(signum: i32, handler: usize) -> usize;
}

/// Rust ignores SIGPIPE, so `println!` into a closed pipe (`matte … | head`) would panic.
/// Restore the default action: the process ends quietly, as other command-line tools do.
/// Windows has no SIGPIPE: there this does nothing, and a closed pipe still ends the command
/// with `println!`'s panic.
fn reset_sigpipe() {
    #[cfg(unix)]
    // SAFETY: setting SIGPIPE (13 on Linux, macOS and the BSDs) to SIG_DFL (0) before any
    // thread starts.
    unsafe {
        signal(13, 0);
    }
}

fn main() -> ExitCode {
    reset_sigpipe();
    let result = matte::cli::parse().and_then(matte::cli::run);
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("matte: error: {}", matte::cli::one_line(&e));
            ExitCode::from(2)
        }
    }
}
