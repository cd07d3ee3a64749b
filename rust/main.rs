use std::process::ExitCode;

fn main() -> ExitCode {
    let result = matte::cli::parse().and_then(matte::cli::run);
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("matte: error: {e}");
            ExitCode::from(2)
        }
    }
}
