//! `matte bench`: the speed targets, matte against the installed Mitsuba in one run (table on
//! stdout, `bench.json` in the output folder).

use crate::bench::{self, BenchOptions};
use clap::Args;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Tiny images, one repeat: checks that everything runs, measures nothing meaningful.
    #[arg(long)]
    pub quick: bool,
    /// Renders per measurement; the best time counts.
    #[arg(long, default_value_t = 3)]
    pub repeats: u32,
    /// Only the samplers' lobe-level efficiency (`sampling.json`, `sampling.md`;
    /// `docs/sampling.md`): seconds, no renders.
    #[arg(long)]
    pub sampling: bool,
    /// Skip Mitsuba (matte's numbers only, no ratios).
    #[arg(long)]
    pub no_mitsuba: bool,
    #[arg(short, long, default_value = "bench_out")]
    pub out: PathBuf,
    #[arg(short, long)]
    pub quiet: bool,
}

pub fn run(a: &BenchArgs) -> Result<(), String> {
    if a.repeats == 0 {
        return Err("--repeats must be at least 1".into());
    }
    std::fs::create_dir_all(&a.out).map_err(|e| format!("{}: {e}", a.out.display()))?;
    if a.sampling {
        let rows = bench::sampling::measure(a.quick);
        let table = bench::sampling::table(&rows);
        for (name, text) in
            [("sampling.json", serde_json::to_string_pretty(&rows).expect("json")), ("sampling.md", table.clone())]
        {
            let path = a.out.join(name);
            std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        }
        print!("{table}");
        return Ok(());
    }
    let scenes = crate::installation::scenes_dir()?;
    let opts = BenchOptions { quick: a.quick, repeats: a.repeats, mitsuba: !a.no_mitsuba, out: a.out.clone(), scenes };
    let m = bench::run(&opts, &|step| {
        if !a.quiet {
            eprintln!("bench: {step}");
        }
    })?;
    let path = a.out.join("bench.json");
    std::fs::write(&path, serde_json::to_string_pretty(&bench::report::json(&m)).expect("json"))
        .map_err(|e| format!("{}: {e}", path.display()))?;
    print!("{}", bench::report::table(&m));
    println!("\n(JSON: {})", path.display());
    Ok(())
}
