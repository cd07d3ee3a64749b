//! Property tags → [`Value`] (`src/core/parser.cpp::parse_xml_node`, the Float, Integer,
//! Boolean, String, Point/Vector, RGB and Spectrum cases; `src/core/properties.cpp::
//! Spectrum::Spectrum(string_view)`; docs/renderer-semantics.md §1 "Property tags").

use super::attrs::Attrs;
use super::numbers::{parse_bool, parse_f64, parse_i64, tokenize};
use super::properties::{Spectrum, Value};
use crate::error::SceneError;

/// Whether `tag` is a property tag handled by [`property_value`] (`<transform>` is separate).
pub(crate) fn is_value_tag(tag: &str) -> bool {
    matches!(tag, "integer" | "float" | "boolean" | "string" | "rgb" | "spectrum" | "point" | "vector")
}

/// The value of a property element; checks its attributes (`name` is required everywhere).
pub(crate) fn property_value(a: &mut Attrs) -> Result<Value, SceneError> {
    let tag = a.tag.clone();
    match tag.as_str() {
        "integer" => {
            a.check(&["!name", "!value"])?;
            let s = a.required("value")?;
            parse_i64(s).map(Value::Integer).ok_or_else(|| a.err(format!("could not parse integer value \"{s}\"")))
        }
        "float" => {
            a.check(&["!name", "!value"])?;
            let s = a.required("value")?;
            parse_f64(s).map(Value::Float).ok_or_else(|| a.err(format!("could not parse float value \"{s}\"")))
        }
        "boolean" => {
            a.check(&["!name", "!value"])?;
            let s = a.required("value")?;
            parse_bool(s)
                .map(Value::Boolean)
                .ok_or_else(|| a.err(format!("could not parse boolean value \"{s}\" (must be \"true\" or \"false\")")))
        }
        "string" => {
            a.check(&["!name", "!value"])?;
            Ok(Value::String(a.required("value")?.to_string()))
        }
        "rgb" => {
            a.check(&["!name", "!value"])?;
            rgb(a)
        }
        "spectrum" => {
            a.check(&["!name", "value", "filename"])?;
            spectrum(a)
        }
        "point" | "vector" => {
            a.expand_value_to_xyz()?;
            a.check(&["!name", "!x", "!y", "!z"])?;
            let v = a.xyz(0.0)?;
            Ok(if tag == "point" { Value::Point(v) } else { Value::Vector(v) })
        }
        other => Err(a.err(format!("<{other}> is not a property tag"))),
    }
}

/// One number (gray) or three, separated by spaces and/or commas.
fn rgb(a: &Attrs) -> Result<Value, SceneError> {
    let s = a.required("value")?;
    let tokens = tokenize(s);
    if tokens.len() != 1 && tokens.len() != 3 {
        return Err(a.err(format!("<rgb> requires one or three values, got {} (\"{s}\")", tokens.len())));
    }
    let mut c = [0.0; 3];
    for (i, t) in tokens.iter().enumerate() {
        c[i] = parse_f64(t).ok_or_else(|| a.err(format!("could not parse RGB value \"{s}\"")))?;
    }
    if tokens.len() == 1 {
        c = [c[0]; 3];
    }
    Ok(Value::Rgb(c))
}

/// `value="v"` (constant) or `value="λ:v λ:v ..."` (≥ 2 pairs, wavelengths strictly
/// increasing). Spectrum files (`filename=`): [`spectrum_file`].
fn spectrum(a: &Attrs) -> Result<Value, SceneError> {
    let value = a.get("value").unwrap_or("");
    let filename = a.get("filename").unwrap_or("");
    if value.is_empty() == filename.is_empty() {
        return Err(a.err("<spectrum> requires either a \"value\" or a \"filename\" attribute (but not both)"));
    }
    if !filename.is_empty() {
        return Err(
            a.err(format!("<spectrum filename=\"{filename}\">: internal: spectrum files are read by the parser"))
        );
    }
    let tokens = tokenize(value);
    if tokens.len() == 1 && !tokens[0].contains(':') {
        let v = parse_f64(tokens[0]).ok_or_else(|| a.err(format!("could not parse spectrum value \"{value}\"")))?;
        return Ok(Value::Spectrum(Spectrum::Constant(v)));
    }
    let mut samples = Vec::with_capacity(tokens.len());
    for t in &tokens {
        let pair: Vec<&str> = t.split(':').filter(|p| !p.is_empty()).collect();
        let parsed = match pair.as_slice() {
            [w, v] => parse_f64(w).zip(parse_f64(v)),
            _ => None,
        };
        let (w, v) = parsed.ok_or_else(|| {
            a.err(format!("could not parse spectrum sample \"{t}\" (expected wavelength:value pairs)"))
        })?;
        samples.push((w, v));
    }
    if samples.len() < 2 {
        return Err(a.err(format!("a sampled spectrum needs at least two wavelength:value pairs (\"{value}\")")));
    }
    if samples.windows(2).any(|s| s[1].0.partial_cmp(&s[0].0) != Some(std::cmp::Ordering::Greater)) {
        return Err(a.err(format!("spectrum wavelengths must be strictly increasing (\"{value}\")")));
    }
    Ok(Value::Spectrum(Spectrum::Sampled(samples)))
}

/// `<spectrum name filename>` whose file was resolved to `path` (Mitsuba's
/// `Properties::Spectrum(const fs::path &)`, `src/core/properties.cpp`): one `λ value` pair per
/// line (anything after the two numbers is ignored), lines starting with `#` and empty lines
/// skipped, at least two pairs, wavelengths strictly increasing.
pub(crate) fn spectrum_file(a: &Attrs, path: &std::path::Path) -> Result<Value, SceneError> {
    a.check(&["!name", "filename"])?;
    let text = std::fs::read_to_string(path)
        .map_err(|e| a.err(format!("cannot read spectrum file \"{}\": {e}", path.display())))?;
    let mut samples = Vec::new();
    for (i, line) in text.split('\n').enumerate() {
        if line.is_empty() || line.starts_with('#') || line.starts_with('\r') {
            continue;
        }
        let mut numbers = line.split_whitespace();
        let mut next = |what: &str| {
            numbers.next().and_then(parse_f64).ok_or_else(|| {
                a.err(format!(
                    "could not extract {what} in line {} of spectrum file \"{}\": \"{}\"",
                    i + 1,
                    path.display(),
                    line.trim_end()
                ))
            })
        };
        let w = next("wavelength")?;
        samples.push((w, next("value")?));
    }
    if samples.len() < 2 {
        return Err(a.err(format!("spectrum file \"{}\" must have at least two entries", path.display())));
    }
    if samples.windows(2).any(|s| s[1].0.partial_cmp(&s[0].0) != Some(std::cmp::Ordering::Greater)) {
        return Err(a.err(format!("spectrum file \"{}\": wavelengths must be strictly increasing", path.display())));
    }
    Ok(Value::Spectrum(Spectrum::Sampled(samples)))
}
