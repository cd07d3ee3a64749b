//! `matte types`: the registered diffuse models (`matte_brdf::MODELS`), as plugin names (one
//! per line; the plugin build reads them), as JSON (every parameter with its kind, default,
//! range, lane clamp and fit bounds, the example configurations the tests sweep, the sampler; the
//! wheel holds it, `matte_mitsuba.registry` reads it) or as the README's model table.

use matte_brdf::registry::{ModelSpec, ParamKind, ParamSpec};

#[derive(clap::Args, Debug)]
pub struct TypesArgs {
    /// Every model's declaration as JSON.
    #[arg(long, conflicts_with = "markdown")]
    pub json: bool,
    /// The README's "Models and parameters" table (Markdown).
    #[arg(long)]
    pub markdown: bool,
}

pub fn run(a: &TypesArgs) -> Result<(), String> {
    if a.json {
        println!("{}", serde_json::to_string_pretty(&json()).map_err(|e| e.to_string())?);
    } else if a.markdown {
        print!("{}", markdown_table());
    } else {
        matte_brdf::BSDF_TYPES.iter().for_each(|t| println!("{t}"));
    }
    Ok(())
}

/// The registry as JSON: every declaration, plus `"samplers"`, the samplers the model offers
/// (the choices of its `sampling` parameter, else only `"cosine"`), and `"sampler"`, its
/// default's.
pub fn json() -> serde_json::Value {
    use matte_brdf::registry::ParamKind;
    let mut all = serde_json::to_value(matte_brdf::MODELS).expect("the declarations serialise");
    for (value, spec) in all.as_array_mut().expect("an array").iter_mut().zip(matte_brdf::MODELS) {
        let (samplers, default): (&[&str], &str) = match spec.param("sampling").map(|p| &p.kind) {
            Some(ParamKind::Choice { choices, default }) => (choices, default),
            _ => (&["cosine"], "cosine"),
        };
        value["samplers"] = samplers.into();
        value["sampler"] = default.into();
    }
    all
}

/// The README's model table, one row per registered model.
pub fn markdown_table() -> String {
    let mut s = String::from("| type | parameters (default) | what it is |\n|---|---|---|\n");
    for m in matte_brdf::MODELS {
        s += &format!("| `{}` | {} | {} |\n", m.name, parameters_cell(m), m.summary);
    }
    s
}

fn parameters_cell(m: &ModelSpec) -> String {
    if m.params.is_empty() {
        return "none".into();
    }
    let mut cell = m.params.iter().map(parameter).collect::<Vec<_>>().join("; ");
    if m.params.iter().any(|p| matches!(p.kind, ParamKind::Ior { .. })) {
        cell += " (indices: numbers or names, `bk7`, `water`, …)";
    }
    cell
}

fn parameter(p: &ParamSpec) -> String {
    match p.kind {
        ParamKind::Number { default } | ParamKind::Ior { default } => format!("`{}` ({default})", p.name),
        ParamKind::Choice { choices, .. } => {
            let words: Vec<String> = choices.iter().map(|c| format!("`{c}`")).collect();
            format!("`{}` = {}", p.name, words.join(" \\| "))
        }
        ParamKind::Flag { default } => format!("`{}` ({default})", p.name),
        ParamKind::File => format!("`{}` (required: {})", p.name, p.doc),
    }
}
