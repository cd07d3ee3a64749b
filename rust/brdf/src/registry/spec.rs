//! A model's declaration as the front ends see it: [`ModelSpec`] (plugin name, label,
//! parameters, examples) and [`ParamSpec`] (a parameter's kind, default, valid range and the
//! clamp of its per-lane values).

use crate::cltc::Sampling;
use crate::params::{ParamError, ParamValue};

/// One model as the front ends see it.
#[derive(Debug, serde::Serialize)]
pub struct ModelSpec {
    /// The plugin name (`<bsdf type="...">`, `matte brdf KIND`).
    pub name: &'static str,
    /// The name in tables, reports and sentences ("Oren–Nayar").
    pub label: &'static str,
    /// One line for tables: the model and its source.
    pub summary: &'static str,
    pub params: &'static [ParamSpec],
    /// Parameter sets the test sweeps run besides the defaults (`name`, value as written in
    /// a scene), e.g. the other `model` of Oren–Nayar or a large roughness.
    pub examples: &'static [&'static [(&'static str, &'static str)]],
    /// Rendered at its defaults in the study's main run (`rust/matte/src/study/configuration.rs`),
    /// beside the paper's models. False for a model that re-parametrises another.
    pub in_study: bool,
}

/// One parameter of a model.
#[derive(Debug, serde::Serialize)]
pub struct ParamSpec {
    pub name: &'static str,
    pub kind: ParamKind,
    /// The values accepted as a number (numeric kinds).
    pub range: Range,
    /// Per-lane (textured) values are clamped into `[lo, hi]`, NaN to `lo`
    /// (`docs/models.md#spatially-varying-parameters`); numeric kinds only.
    pub lane_clamp: (f64, f64),
    /// Where an inverse-rendering fit (`matte fit`, `python/matte_mitsuba/fit.py`) may search:
    /// the fitted value is clamped into `[lo, hi]` after every step. Within `range` and the
    /// lane clamp (checked at compile time by `models!`); numeric kinds only. By default the
    /// range's bounds ([`ParamSpec::with_fit`] for others: away from a stationary point, or
    /// an upper bound for an open range).
    pub fit: (f64, f64),
    /// What a valid value is, completing "must ...": the error text for a value outside
    /// `range` ("be a finite angle >= 0 in radians").
    pub what: &'static str,
    /// For the README's model table: the meaning and unit.
    pub doc: &'static str,
}

/// How a parameter is given.
#[derive(Debug, PartialEq, serde::Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum ParamKind {
    /// A number; texturable (a `<texture>` gives it per lane).
    Number { default: f64 },
    /// An index of refraction: a number or one of Mitsuba's named materials; texturable.
    Ior { default: f64 },
    /// One word of `choices` (case-insensitive).
    Choice { choices: &'static [&'static str], default: &'static str },
    /// A boolean.
    Flag { default: bool },
    /// A file the model reads when it is built (`tabulated_brdf`'s table); required. Front
    /// ends resolve the name as they resolve every file of a scene (next to the scene, then the
    /// search path) before handing it over.
    File,
}

/// The valid numbers of a numeric parameter (always finite, within `MAX_MAGNITUDE`).
#[derive(Clone, Copy, Debug, serde::Serialize)]
#[serde(tag = "type", content = "bounds", rename_all = "snake_case")]
pub enum Range {
    /// `x ≥ lo`.
    AtLeast(f64),
    /// `lo ≤ x ≤ hi`.
    Closed(f64, f64),
    /// `lo < x ≤ hi`.
    OpenClosed(f64, f64),
}

impl Range {
    pub const fn contains(self, x: f64) -> bool {
        match self {
            Range::AtLeast(lo) => x >= lo,
            Range::Closed(lo, hi) => lo <= x && x <= hi,
            Range::OpenClosed(lo, hi) => lo < x && x <= hi,
        }
    }
}

impl ParamSpec {
    /// A number in `range`; its per-lane values are clamped into the range's bounds.
    pub const fn number(name: &'static str, default: f64, range: Range, what: &'static str, doc: &'static str) -> Self {
        let lane_clamp = match range {
            Range::AtLeast(lo) => (lo, f64::INFINITY),
            Range::Closed(lo, hi) | Range::OpenClosed(lo, hi) => (lo, hi),
        };
        Self { name, kind: ParamKind::Number { default }, range, lane_clamp, fit: lane_clamp, what, doc }
    }

    /// A number in [0, 1] (a roughness).
    pub const fn unit_interval(name: &'static str, default: f64, doc: &'static str) -> Self {
        Self::number(name, default, Range::Closed(0.0, 1.0), "lie in [0, 1]", doc)
    }

    /// An index of refraction (a number ≥ 1 or a named material). A fit searches [1, 4]: the
    /// named materials reach 2.42 (diamond).
    pub const fn ior(name: &'static str, default: f64, doc: &'static str) -> Self {
        Self {
            name,
            kind: ParamKind::Ior { default },
            range: Range::AtLeast(1.0),
            lane_clamp: (1.0, f64::INFINITY),
            fit: (1.0, 4.0),
            what: "be a finite index of refraction >= 1",
            doc,
        }
    }

    /// One word of `choices`.
    pub const fn choice(
        name: &'static str,
        choices: &'static [&'static str],
        default: &'static str,
        doc: &'static str,
    ) -> Self {
        Self { kind: ParamKind::Choice { choices, default }, ..Self::word(name, doc) }
    }

    /// The `sampling` parameter of a model with its own sampler (`docs/sampling.md`): a choice
    /// of [`Sampling`], default `cosine`; `doc` says what `cltc` is.
    pub const fn sampling(doc: &'static str) -> Self {
        Self::choice("sampling", Sampling::CHOICES, "cosine", doc)
    }

    /// A boolean.
    pub const fn flag(name: &'static str, default: bool, doc: &'static str) -> Self {
        Self { kind: ParamKind::Flag { default }, ..Self::word(name, doc) }
    }

    /// A required file name.
    pub const fn file(name: &'static str, doc: &'static str) -> Self {
        Self { kind: ParamKind::File, ..Self::word(name, doc) }
    }

    const fn word(name: &'static str, doc: &'static str) -> Self {
        Self {
            name,
            kind: ParamKind::Flag { default: false },
            range: Range::AtLeast(f64::NEG_INFINITY),
            lane_clamp: (f64::NEG_INFINITY, f64::INFINITY),
            fit: (f64::NEG_INFINITY, f64::INFINITY),
            what: "",
            doc,
        }
    }

    /// The same parameter with per-lane values clamped into `[lo, hi]` instead.
    pub const fn with_lane_clamp(self, lo: f64, hi: f64) -> Self {
        Self { lane_clamp: (lo, hi), ..self }
    }

    /// The same parameter with a fit searching `[lo, hi]` instead ([`ParamSpec::fit`]).
    pub const fn with_fit(self, lo: f64, hi: f64) -> Self {
        Self { fit: (lo, hi), ..self }
    }

    /// Whether a numeric parameter's fit bounds lie within its range and its lane clamp, lower
    /// below upper (true for the other kinds).
    pub const fn fit_is_valid(&self) -> bool {
        let ((lo, hi), (clamp_lo, clamp_hi)) = (self.fit, self.lane_clamp);
        !self.is_numeric()
            || (lo < hi && self.range.contains(lo) && self.range.contains(hi) && clamp_lo <= lo && hi <= clamp_hi)
    }

    /// A number or an index of refraction: the parameters a texture may give.
    pub const fn is_numeric(&self) -> bool {
        matches!(self.kind, ParamKind::Number { .. } | ParamKind::Ior { .. })
    }

    /// The default as a [`ParamValue`] (what `parameters()` reports when nothing is given);
    /// `None` for a required parameter.
    pub fn default_value(&self) -> Option<ParamValue> {
        match self.kind {
            ParamKind::Number { default } | ParamKind::Ior { default } => Some(ParamValue::Number(default)),
            ParamKind::Choice { default, .. } => Some(ParamValue::Text(default.into())),
            ParamKind::Flag { default } => Some(ParamValue::Flag(default)),
            ParamKind::File => None,
        }
    }

    /// `x` if it lies in the range, else the error naming the parameter.
    pub fn check(&self, x: f64) -> Result<f64, ParamError> {
        if self.range.contains(x) {
            Ok(x)
        } else {
            Err(ParamError::new(self.name, format!("must {} (got {x})", self.what)))
        }
    }

    /// `mean` clamped into the lane clamp (NaN gives the lower bound).
    pub fn clamp_lane(&self, mean: f64) -> f64 {
        let (lo, hi) = self.lane_clamp;
        if mean >= lo { mean.min(hi) } else { lo }
    }
}

impl ModelSpec {
    pub fn param(&self, name: &str) -> Option<&'static ParamSpec> {
        self.params.iter().find(|p| p.name == name)
    }

    /// The model's own sampler, the choice of its `sampling` parameter that is not the cosine
    /// (`docs/sampling.md`), if it offers one.
    pub fn own_sampler(&self) -> Option<&'static str> {
        match self.param("sampling")?.kind {
            ParamKind::Choice { choices, .. } => choices.iter().copied().find(|c| *c != "cosine"),
            _ => None,
        }
    }

    /// The numeric parameters in order: the order per-lane values are given in.
    pub fn numeric(&self) -> impl Iterator<Item = &'static ParamSpec> {
        self.params.iter().filter(|p| p.is_numeric())
    }

    pub fn names(&self) -> Vec<&'static str> {
        self.params.iter().map(|p| p.name).collect()
    }

    /// Whether the model builds from its defaults alone: no required parameter (a file). The
    /// sweeps over every model at its defaults (tests, `matte bench`) run these.
    pub fn builds_from_defaults(&self) -> bool {
        self.params.iter().all(|p| p.default_value().is_some())
    }
}

/// Whether every parameter of `spec` has valid fit bounds ([`ParamSpec::fit_is_valid`]; a
/// `const fn`, for the compile-time check of `models!`).
pub const fn fits_are_valid(spec: &ModelSpec) -> bool {
    let mut i = 0;
    while i < spec.params.len() {
        if !spec.params[i].fit_is_valid() {
            return false;
        }
        i += 1;
    }
    true
}

/// Counts the numeric parameters of `spec` (a `const fn`, for the compile-time limit below).
pub const fn numeric_count(spec: &ModelSpec) -> usize {
    let (mut i, mut n) = (0, 0);
    while i < spec.params.len() {
        if spec.params[i].is_numeric() {
            n += 1;
        }
        i += 1;
    }
    n
}

/// The most numeric parameters a model may have: the renderer keeps a hit's per-lane values
/// in a fixed array of this size (no allocation per hit). Raising it is this one constant.
pub const MAX_NUMERIC: usize = 2;
