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

/// A parameter value: what a front end gives for one parameter (a `<bsdf>` property, a CLI
/// `--param`, a test's pair) and what a model reports as its effective value
/// ([`crate::DiffuseModel::parameters`]). In JSON a number is the number, text and a flag the
/// string (`"true"`, as the XML writes it), a texture its mean.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamValue {
    /// `<float>`, `<integer>`, a number on the command line.
    Number(f64),
    /// `<string>`: a choice, a named index of refraction, a file name.
    Text(String),
    /// `<boolean>`.
    Flag(bool),
    /// A nested `<texture>`, given by its mean: [`crate::construction::construct`] builds and
    /// validates the model with the number it stands for (the mean clamped into the
    /// parameter's per-lane range) and marks the parameter textured.
    Texture { mean: f64 },
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

impl From<bool> for ParamValue {
    fn from(b: bool) -> Self {
        ParamValue::Flag(b)
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
    /// A value as written in a scene or on the command line (`--param k=v`, a SPEC's
    /// examples): a number if the text parses as one, a flag for `true` and `false`, else the
    /// text itself.
    pub fn parse(text: &str) -> Self {
        let text = text.trim();
        match (text.parse::<f64>(), text) {
            (Ok(x), _) => ParamValue::Number(x),
            (Err(_), "true") => ParamValue::Flag(true),
            (Err(_), "false") => ParamValue::Flag(false),
            (Err(_), _) => ParamValue::Text(text.to_string()),
        }
    }

    /// The value as a word, where a word is read (a choice, a named index of refraction, a
    /// file name): text itself, a flag as `true` or `false`; `None` for a number.
    fn word(&self) -> Option<String> {
        match self {
            ParamValue::Text(s) => Some(s.clone()),
            ParamValue::Flag(b) => Some(b.to_string()),
            ParamValue::Number(_) | ParamValue::Texture { .. } => None,
        }
    }
}

impl serde::Serialize for ParamValue {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            ParamValue::Number(x) | ParamValue::Texture { mean: x } => s.serialize_f64(*x),
            ParamValue::Text(t) => s.serialize_str(t),
            ParamValue::Flag(b) => s.serialize_str(if *b { "true" } else { "false" }),
        }
    }
}

impl fmt::Display for ParamValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParamValue::Number(x) => write!(f, "{x}"),
            ParamValue::Text(s) => write!(f, "\"{s}\""),
            ParamValue::Flag(b) => write!(f, "{b}"),
            ParamValue::Texture { mean } => write!(f, "a texture of mean {mean}"),
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

/// The error as the front ends print it (`?` in functions that return `Result<_, String>`).
impl From<ParamError> for String {
    fn from(e: ParamError) -> Self {
        e.to_string()
    }
}

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
            Some(ParamValue::Number(x) | ParamValue::Texture { mean: x }) => bounded(name, x),
            Some(v) => {
                Err(ParamError::new(name, format!("must be a number (got \"{}\")", v.word().unwrap_or_default())))
            }
        }
    }

    /// One of `choices`, `default` if absent.
    pub fn choice<'c>(&mut self, name: &str, choices: &[&'c str], default: &'c str) -> Result<&'c str, ParamError> {
        match self.take(name)? {
            None => Ok(default),
            Some(v) => one_of(name, choices, &v),
        }
    }

    /// A boolean (`<boolean>`; as text, `true` or `false`), `default` if absent.
    pub fn flag(&mut self, name: &str, default: bool) -> Result<bool, ParamError> {
        match self.take(name)? {
            None => Ok(default),
            Some(ParamValue::Flag(b)) => Ok(b),
            Some(v) => Ok(one_of(name, &["true", "false"], &v)? == "true"),
        }
    }

    /// A required file name (`tabulated_brdf`'s table).
    pub fn file(&mut self, name: &str) -> Result<String, ParamError> {
        match self.take(name)? {
            Some(ParamValue::Number(x) | ParamValue::Texture { mean: x }) => {
                Err(ParamError::new(name, format!("must be a file name (got {x})")))
            }
            Some(v) => match v.word() {
                Some(s) if !s.is_empty() => Ok(s),
                _ => Err(ParamError::new(name, "must name a file (got \"\")")),
            },
            None => Err(ParamError::new(name, "is missing (required: the file to read)")),
        }
    }

    /// An index of refraction: a number (within [`MAX_MAGNITUDE`]) or one of Mitsuba's named
    /// materials.
    pub fn ior(&mut self, name: &str, default: f64) -> Result<f64, ParamError> {
        match self.take(name)? {
            None => Ok(default),
            Some(ParamValue::Number(x) | ParamValue::Texture { mean: x }) => bounded(name, x),
            Some(v) => {
                let s = v.word().unwrap_or_default();
                lookup_ior(&s).ok_or_else(|| {
                    let names: Vec<&str> = NAMED_IORS.iter().map(|(n, _)| *n).collect();
                    ParamError::new(name, format!("unknown material \"{s}\"; valid names: {}", names.join(", ")))
                })
            }
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

/// The entry of `choices` that `value` names (case-insensitive), or the error naming the
/// parameter.
fn one_of<'c>(name: &str, choices: &[&'c str], value: &ParamValue) -> Result<&'c str, ParamError> {
    let given = match value {
        ParamValue::Number(x) | ParamValue::Texture { mean: x } => x.to_string(),
        v => v.word().unwrap_or_default(),
    };
    choices
        .iter()
        .find(|c| c.eq_ignore_ascii_case(&given))
        .copied()
        .ok_or_else(|| ParamError::new(name, format!("must be one of {} (got \"{given}\")", choices.join(", "))))
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
