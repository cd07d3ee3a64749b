//! `matte tables`: matte's values for the reference configurations of
//! `docs/models.md#reference-values` (Table 1: f at ρ = 0.8; Table 2: white-furnace albedo), so a
//! reader can hold them against the published numbers, plus the van Ginneken fast path's
//! measured error against the reference integral.

use clap::Args;
use matte_brdf::ginneken::Ginneken;
use matte_brdf::ginneken::accuracy::fast_path_accuracy;
use matte_brdf::ginneken::shadowing::Shadowing;

/// Roughnesses whose van Ginneken fast-path error is printed besides the tables' own (0.3, 0.5).
const FAST_PATH_ROUGHNESS: [f64; 5] = [0.02, 0.1, 1.0, 2.0, 4.0];
use matte_brdf::reference_values::TABLE1_COLUMNS;
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue, frame::spherical_direction};

#[derive(Args, Debug)]
pub struct TablesArgs {
    /// Configurations used to measure the van Ginneken fast path (0 skips it).
    #[arg(long, default_value_t = 20000)]
    pub error_samples: usize,
}

/// A table row: (label, plugin type, parameters as XML name/value pairs).
type Row = (&'static str, &'static str, &'static [(&'static str, &'static str)]);

/// The rows, in the notation of `docs/models.md` Tables 1–2.
const ROWS: &[Row] = &[
    ("Lambert", "lambert", &[]),
    ("QON s=0.25", "oren_nayar", &[("sigma", "0.25")]),
    ("QON s=0.3", "oren_nayar", &[("sigma", "0.3")]),
    ("QON s=0.5", "oren_nayar", &[("sigma", "0.5")]),
    ("QON s=1.0", "oren_nayar", &[("sigma", "1.0")]),
    ("fullON s=0.5 (+L2)", "oren_nayar", &[("sigma", "0.5"), ("model", "full")]),
    ("fullON s=1.0 (+L2)", "oren_nayar", &[("sigma", "1.0"), ("model", "full")]),
    ("EON r=0.5", "eon", &[("roughness", "0.5")]),
    ("EON r=1", "eon", &[("roughness", "1.0")]),
    ("Wolff raw n=1.5", "wolff", &[("int_ior", "1.5"), ("normalization", "raw")]),
    ("Wolff normal n=1.5", "wolff", &[("int_ior", "1.5"), ("normalization", "normal")]),
    ("Wolff phys n=1.5", "wolff", &[("int_ior", "1.5")]),
    ("vG m=0.3", "ginneken", &[("roughness", "0.3")]),
    ("vG m=0.3 (height-corr.)", "ginneken", &[("roughness", "0.3"), ("shadowing", "height_correlated")]),
    ("vG m=0.5", "ginneken", &[("roughness", "0.5")]),
];

const TABLE2_ANGLES: &[f64] = &[0.0, 30.0, 60.0, 80.0, 89.0];

pub fn run(args: &TablesArgs) -> Result<(), String> {
    let models: Vec<(&str, DiffuseModel)> = ROWS
        .iter()
        .map(|(l, k, p)| {
            let values: Vec<(&str, ParamValue)> = p.iter().map(|(n, v)| (*n, ParamValue::parse(v))).collect();
            DiffuseModel::with(k, &values).map(|b| (*l, b))
        })
        .collect::<Result<_, _>>()?;

    println!("Table 1: f(wi, wo) in 1/sr, reflectance 0.8 (columns: θi/θo/Δφ in degrees)");
    print!("{:<26}", "model");
    for (ti, to, ph) in TABLE1_COLUMNS {
        print!("{:>10}", format!("{ti}/{to}/{ph}"));
    }
    println!();
    for (label, bsdf) in &models {
        print!("{label:<26}");
        for (ti, to, ph) in TABLE1_COLUMNS {
            let wi = spherical_direction(ti.to_radians(), 0.0);
            let wo = spherical_direction(to.to_radians(), ph.to_radians());
            print!("{:>10.5}", bsdf.eval(wi, wo, [0.8])[0]);
        }
        println!();
    }

    println!("\nTable 2: directional albedo E(θi), reflectance 1 (white furnace)");
    print!("{:<26}", "model");
    for t in TABLE2_ANGLES {
        print!("{:>9}", format!("{t}°"));
    }
    println!("  method");
    for (label, bsdf) in &models {
        print!("{label:<26}");
        let mut method = "";
        for t in TABLE2_ANGLES {
            let a = bsdf.albedo(t.to_radians().cos(), 1.0);
            method = a.method.as_str();
            print!("{:>9.4}", a.value);
        }
        println!("  {method}");
    }

    if args.error_samples > 0 {
        println!(
            "\nvan Ginneken fast path vs reference integral ({} quasi-random configurations each)",
            args.error_samples
        );
        // The tables' models, then the rest of the roughness range.
        let others = FAST_PATH_ROUGHNESS.iter().map(|&m| {
            let g = Ginneken::new(m, Shadowing::VanGinneken).expect("a valid roughness");
            (format!("vG m={m}"), DiffuseModel::Ginneken(g))
        });
        let table_models = models.iter().map(|(label, bsdf)| (label.to_string(), bsdf.clone()));
        for (label, bsdf) in table_models.chain(others) {
            if let DiffuseModel::Ginneken(g) = &bsdf {
                for max_theta in [80.0, 85.0, 89.0] {
                    let e = fast_path_accuracy(g, max_theta, args.error_samples);
                    println!(
                        "{label:<26} θ ≤ {max_theta}°: max {:.3} %, mean {:.4} % (worst at {:.1}/{:.1}/{:.1})",
                        100.0 * e.max_relative,
                        100.0 * e.mean_relative,
                        e.worst.0,
                        e.worst.1,
                        e.worst.2
                    );
                }
            }
        }
    }
    Ok(())
}
