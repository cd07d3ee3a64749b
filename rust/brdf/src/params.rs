//! Parameter lists and their validation, shared by the CLI, the Rust renderer's scene loader
//! and the Mitsuba plugin: every front end hands over `name = value` pairs and gets back a
//! constructed model or a [`ParamError`] naming the offending parameter.

use std::fmt;

/// Largest magnitude matte accepts for any number a model, IOR or BSDF parameter is built
/// from, in every front end (CLI, the renderer's loader, the Mitsuba plugin). The f32 kernels
/// overflow into NaN around 1e15–1e19 (e.g. η⁴ in a Fresnel term), long after values stopped
/// meaning anything physically; Mitsuba itself takes any float.
pub const MAX_MAGNITUDE: f64 = 1e6;

/// The error text for a number beyond [`MAX_MAGNITUDE`].
pub fn too_large(v: f64) -> String {
    format!("is {v}; matte accepts magnitudes up to {MAX_MAGNITUDE:e}")
}

/// A finite number within [`MAX_MAGNITUDE`], or the reason it is not.
fn bounded(name: &str, x: f64) -> Result<f64, ParamError> {
    if !x.is_finite() {
        Err(ParamError::new(name, format!("must be a finite number (got {x})")))
    } else if x.abs() > MAX_MAGNITUDE {
        Err(ParamError::new(name, too_large(x)))
    } else {
        Ok(x)
    }
}

/// A parameter value as the front ends deliver it: a number or a word
/// (`model=full`, `int_ior=bk7`). In JSON it is the number or the string itself.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(untagged)]
pub enum ParamValue {
    Number(f64),
    Text(String),
}

impl From<f64> for ParamValue {
    fn from(x: f64) -> Self {
        ParamValue::Number(x)
    }
}

/// A number as a model stores it.
impl From<f32> for ParamValue {
    fn from(x: f32) -> Self {
        ParamValue::Number(x as f64)
    }
}

/// A flag as text (`true`, `false`).
impl From<bool> for ParamValue {
    fn from(b: bool) -> Self {
        ParamValue::Text(b.to_string())
    }
}

impl From<&str> for ParamValue {
    fn from(s: &str) -> Self {
        ParamValue::Text(s.into())
    }
}

impl From<String> for ParamValue {
    fn from(s: String) -> Self {
        ParamValue::Text(s)
    }
}

impl ParamValue {
    /// A number if the text parses as one, else the text itself (CLI `--param k=v`).
    pub fn parse(text: &str) -> Self {
        match text.trim().parse::<f64>() {
            Ok(x) => ParamValue::Number(x),
            Err(_) => ParamValue::Text(text.trim().to_string()),
        }
    }
}

impl fmt::Display for ParamValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParamValue::Number(x) => write!(f, "{x}"),
            ParamValue::Text(s) => write!(f, "\"{s}\""),
        }
    }
}

/// A rejected parameter: which one and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParamError {
    pub param: String,
    pub message: String,
}

impl ParamError {
    pub fn new(param: &str, message: impl Into<String>) -> Self {
        Self { param: param.to_string(), message: message.into() }
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "parameter \"{}\": {}", self.param, self.message)
    }
}

impl std::error::Error for ParamError {}

/// The parameters given for one BSDF. Readers mark what they consume; [`Params::finish`]
/// rejects whatever was not consumed (unknown parameter names), as Mitsuba's parser does.
#[derive(Clone, Debug, Default)]
pub struct Params {
    entries: Vec<(String, ParamValue, bool)>,
}

impl Params {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn with(mut self, name: &str, value: ParamValue) -> Self {
        self.push(name, value);
        self
    }

    pub fn push(&mut self, name: &str, value: ParamValue) {
        self.entries.push((name.to_string(), value, false));
    }

    fn take(&mut self, name: &str) -> Result<Option<ParamValue>, ParamError> {
        let mut found = None;
        for (n, v, used) in &mut self.entries {
            if n == name {
                if found.is_some() {
                    return Err(ParamError::new(name, "given more than once"));
                }
                *used = true;
                found = Some(v.clone());
            }
        }
        Ok(found)
    }

    /// A finite number of magnitude at most [`MAX_MAGNITUDE`], `default` if absent.
    pub fn number(&mut self, name: &str, default: f64) -> Result<f64, ParamError> {
        match self.take(name)? {
            None => Ok(default),
            Some(ParamValue::Number(x)) => bounded(name, x),
            Some(ParamValue::Text(s)) => Err(ParamError::new(name, format!("must be a number (got \"{s}\")"))),
        }
    }

    /// One of `choices`, `default` if absent.
    pub fn choice<'c>(&mut self, name: &str, choices: &[&'c str], default: &'c str) -> Result<&'c str, ParamError> {
        let given = match self.take(name)? {
            None => return Ok(default),
            Some(ParamValue::Text(s)) => s,
            Some(ParamValue::Number(x)) => x.to_string(),
        };
        choices
            .iter()
            .find(|c| c.eq_ignore_ascii_case(&given))
            .copied()
            .ok_or_else(|| ParamError::new(name, format!("must be one of {} (got \"{given}\")", choices.join(", "))))
    }

    /// A boolean (`<boolean>` in XML reaches the kernels as the text "true" / "false"),
    /// `default` if absent.
    pub fn flag(&mut self, name: &str, default: bool) -> Result<bool, ParamError> {
        Ok(self.choice(name, &["true", "false"], if default { "true" } else { "false" })? == "true")
    }

    /// A required file name (`tabulated_brdf`'s table).
    pub fn file(&mut self, name: &str) -> Result<String, ParamError> {
        match self.take(name)? {
            Some(ParamValue::Text(s)) if !s.is_empty() => Ok(s),
            Some(ParamValue::Text(_)) => Err(ParamError::new(name, "must name a file (got \"\")")),
            Some(ParamValue::Number(x)) => Err(ParamError::new(name, format!("must be a file name (got {x})"))),
            None => Err(ParamError::new(name, "is missing (required: the file to read)")),
        }
    }

    /// An index of refraction: a number (within [`MAX_MAGNITUDE`]) or one of Mitsuba's named
    /// materials.
    pub fn ior(&mut self, name: &str, default: f64) -> Result<f64, ParamError> {
        match self.take(name)? {
            None => Ok(default),
            Some(ParamValue::Number(x)) => bounded(name, x),
            Some(ParamValue::Text(s)) => lookup_ior(&s).ok_or_else(|| {
                let names: Vec<&str> = NAMED_IORS.iter().map(|(n, _)| *n).collect();
                ParamError::new(name, format!("unknown material \"{s}\"; valid names: {}", names.join(", ")))
            }),
        }
    }

    /// Error for the first parameter nobody asked for.
    pub fn finish(&self, bsdf: &str, known: &[&str]) -> Result<(), ParamError> {
        match self.entries.iter().find(|(_, _, used)| !used) {
            None => Ok(()),
            Some((n, _, _)) => {
                Err(ParamError::new(n, format!("unknown parameter for bsdf \"{bsdf}\" (known: {})", known.join(", "))))
            }
        }
    }
}

/// Named indices of refraction, as in Mitsuba 3.9.1 `include/mitsuba/render/ior.h`
/// (Hecht, Optics, 4th ed.; 0–20 °C, ~589 nm) so that scenes written for `plastic` port over.
pub const NAMED_IORS: &[(&str, f64)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// Case-insensitive lookup in [`NAMED_IORS`].
pub fn lookup_ior(name: &str) -> Option<f64> {
    let lower = name.trim().to_ascii_lowercase();
    NAMED_IORS.iter().find(|(n, _)| *n == lower).map(|(_, v)| *v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_parameters_are_named() {
        let mut p = Params::new().with("sigma", ParamValue::Number(0.2)).with("sigmaa", ParamValue::Number(1.0));
        p.number("sigma", 0.3).unwrap();
        let e = p.finish("oren_nayar", &["sigma"]).unwrap_err();
        assert_eq!(e.param, "sigmaa");
    }

    #[test]
    fn iors_by_name_or_number() {
        let mut p = Params::new().with("int_ior", ParamValue::parse("BK7")).with("ext_ior", ParamValue::parse("1.2"));
        assert_eq!(p.ior("int_ior", 1.4).unwrap(), 1.5046);
        assert_eq!(p.ior("ext_ior", 1.0).unwrap(), 1.2);
        let mut q = Params::new().with("int_ior", ParamValue::parse("unobtainium"));
        assert_eq!(q.ior("int_ior", 1.4).unwrap_err().param, "int_ior");
    }

    #[test]
    fn duplicates_and_non_numbers_are_rejected() {
        let mut p = Params::new().with("m", ParamValue::Number(1.0)).with("m", ParamValue::Number(2.0));
        assert!(p.number("m", 0.0).is_err());
        let mut q = Params::new().with("m", ParamValue::parse("abc"));
        assert!(q.number("m", 0.0).is_err());
        let mut r = Params::new().with("m", ParamValue::Number(f64::NAN));
        assert!(r.number("m", 0.0).is_err());
    }
}
