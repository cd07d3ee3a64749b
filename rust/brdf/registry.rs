//! The registry of diffuse models. Each model declares itself once, in its own file: a
//! [`ModelSpec`] (plugin name, parameters with kind, default, valid range, the clamp of its
//! per-lane values and where a fit may search them, example configurations) and an
//! implementation of [`Registered`] (how its kernel is built from those parameters). The list
//! of models is the one [`models!`] call in `rust/brdf/mod.rs`; from it come
//! [`super::DiffuseModel`] and its static dispatch (`dispatch!`), [`super::LaneKernel`],
//! [`super::MODELS`], [`super::BSDF_TYPES`], the parameter parsing of every front end (CLI,
//! scene loader, Mitsuba plugin) and `matte types --json`, which the Python side
//! (`matte_mitsuba.registry`) and the tests read.
//! `docs/adding-a-model.md` walks through adding one.

use super::diffuse_brdf::{Albedo, AlbedoMethod, BrdfSample, DiffuseBrdf, albedo_by_quadrature};
use super::kernel;
use super::kernel::Kernel;
use super::params::{ParamError, ParamValue, Params};
use super::real::Real;
use glam::{Vec2, Vec3};
use std::fmt::Debug;

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
    /// Rendered at its defaults in the study's main run (`rust/study/configuration.rs`),
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
            ParamKind::Flag { default } => Some(ParamValue::Text(default.to_string())),
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

/// A value read for one parameter, after the default was filled in and the range checked.
#[derive(Clone, Debug, PartialEq)]
enum Value {
    Number(f64),
    Choice(&'static str),
    Flag(bool),
    File(String),
}

/// A model's parameters read from [`Params`] by its [`ModelSpec`]: every parameter present
/// (defaults filled in), numbers range-checked. [`Registered::build`] takes them by name.
#[derive(Clone, Debug)]
pub struct Values {
    values: Vec<Value>,
}

impl Values {
    /// Reads every parameter of `spec` from `params` (marking them used; unknown names are
    /// left for [`Params::finish`]).
    pub fn read(spec: &'static ModelSpec, params: &mut Params) -> Result<Self, ParamError> {
        let mut values = Vec::with_capacity(spec.params.len());
        for p in spec.params {
            values.push(match p.kind {
                ParamKind::Number { default } => Value::Number(p.check(params.number(p.name, default)?)?),
                ParamKind::Ior { default } => Value::Number(p.check(params.ior(p.name, default)?)?),
                ParamKind::Choice { choices, default } => Value::Choice(params.choice(p.name, choices, default)?),
                ParamKind::Flag { default } => Value::Flag(params.flag(p.name, default)?),
                ParamKind::File => Value::File(params.file(p.name)?),
            });
        }
        Ok(Self { values })
    }

    fn get<K>(&self, p: Param<K>) -> &Value {
        &self.values[p.index]
    }

    pub fn number(&self, p: Param<kind::Number>) -> f64 {
        match self.get(p) {
            Value::Number(x) => *x,
            _ => unreachable!("Param::of checked the kind"),
        }
    }

    pub fn choice(&self, p: Param<kind::Choice>) -> &'static str {
        match self.get(p) {
            Value::Choice(c) => c,
            _ => unreachable!("Param::of checked the kind"),
        }
    }

    pub fn flag(&self, p: Param<kind::Flag>) -> bool {
        match self.get(p) {
            Value::Flag(b) => *b,
            _ => unreachable!("Param::of checked the kind"),
        }
    }

    /// A file parameter's name (resolved by the front end).
    pub fn file(&self, p: Param<kind::File>) -> &str {
        match self.get(p) {
            Value::File(f) => f,
            _ => unreachable!("Param::of checked the kind"),
        }
    }
}

/// The kinds a [`Param`] is read as: one [`Values`] accessor each.
pub mod kind {
    use super::ParamKind;

    /// A kind of parameter value, as a type.
    pub trait ValueKind {
        /// What [`kind_code`] gives for a parameter of this kind.
        const CODE: u8;
    }

    /// The code of a [`ParamKind`]: numbers and indices of refraction are both numbers.
    pub const fn kind_code(kind: &ParamKind) -> u8 {
        match kind {
            ParamKind::Number { .. } | ParamKind::Ior { .. } => Number::CODE,
            ParamKind::Choice { .. } => Choice::CODE,
            ParamKind::Flag { .. } => Flag::CODE,
            ParamKind::File => File::CODE,
        }
    }

    macro_rules! kinds {
        ($($(#[$m:meta])* $name:ident = $code:literal),+) => {
            $($(#[$m])* #[derive(Clone, Copy, Debug, PartialEq, Eq)] pub struct $name;
            impl ValueKind for $name {
                const CODE: u8 = $code;
            })+
        };
    }
    kinds! {
        /// A number or an index of refraction ([`super::Values::number`]).
        Number = 0,
        /// A word of a choice ([`super::Values::choice`]).
        Choice = 1,
        /// A boolean ([`super::Values::flag`]).
        Flag = 2,
        /// A file name ([`super::Values::file`]).
        File = 3
    }
}

/// A parameter of a model's SPEC by position and kind, for reading [`Values`]: made by
/// [`param!`] at compile time, so a name the SPEC does not declare, or a parameter read as
/// another kind than the SPEC declares (`v.number` of a choice), does not compile.
#[derive(Debug, PartialEq, Eq)]
pub struct Param<K> {
    index: usize,
    kind: std::marker::PhantomData<K>,
}

impl<K> Clone for Param<K> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<K> Copy for Param<K> {}

impl<K: kind::ValueKind> Param<K> {
    /// The parameter `name` of `spec`, of kind `K`; in a `const` context (as [`param!`]
    /// evaluates it), a name `spec` does not declare, or another kind, is a compile error.
    ///
    /// ```
    /// use matte_brdf::registry::{Param, Registered, kind};
    /// const SIGMA: Param<kind::Number> = Param::of(&matte_brdf::OrenNayar::SPEC, "sigma");
    /// ```
    ///
    /// ```compile_fail
    /// use matte_brdf::registry::{Param, Registered, kind};
    /// // Oren–Nayar's `model` is a choice, not a number.
    /// const MODEL: Param<kind::Number> = Param::of(&matte_brdf::OrenNayar::SPEC, "model");
    /// ```
    ///
    /// ```compile_fail
    /// use matte_brdf::registry::{Param, Registered, kind};
    /// const SIGMA: Param<kind::Number> = Param::of(&matte_brdf::OrenNayar::SPEC, "sigmaa");
    /// ```
    pub const fn of(spec: &ModelSpec, name: &str) -> Self {
        let index = index_of(spec, name);
        if kind::kind_code(&spec.params[index].kind) != K::CODE {
            panic!("a model reads a parameter as another kind than its SPEC declares")
        }
        Param { index, kind: std::marker::PhantomData }
    }
}

/// The position of the parameter `name` in `spec` (a compile error in a `const` context if
/// there is none).
pub const fn index_of(spec: &ModelSpec, name: &str) -> usize {
    let mut i = 0;
    while i < spec.params.len() {
        if str_eq(spec.params[i].name, name) {
            return i;
        }
        i += 1;
    }
    panic!("a model names a parameter its SPEC does not declare")
}

/// Whether `names` are the names of `spec`'s parameters, each once, in any order.
pub const fn names_all_parameters(spec: &ModelSpec, names: &[&str]) -> bool {
    if names.len() != spec.params.len() {
        return false;
    }
    let mut i = 0;
    while i < spec.params.len() {
        let mut found = false;
        let mut j = 0;
        while j < names.len() {
            found |= str_eq(spec.params[i].name, names[j]);
            j += 1;
        }
        if !found {
            return false;
        }
        i += 1;
    }
    true
}

/// Whether `names` are the names of `spec`'s numeric parameters, in their order.
pub const fn names_numeric_parameters(spec: &ModelSpec, names: &[&str]) -> bool {
    let (mut i, mut k) = (0, 0);
    while i < spec.params.len() {
        if spec.params[i].is_numeric() {
            if k >= names.len() || !str_eq(spec.params[i].name, names[k]) {
                return false;
            }
            k += 1;
        }
        i += 1;
    }
    k == names.len()
}

const fn str_eq(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// `param!("roughness")` in a [`Registered`] impl: that model's parameter, its name and kind
/// (from the [`Values`] accessor it is given to) checked against its SPEC at compile time
/// ([`Param::of`]).
macro_rules! param {
    ($name:expr) => {
        const { $crate::registry::Param::of(&<Self as $crate::registry::Registered>::SPEC, $name) }
    };
}
pub(crate) use param;

/// `parameter_values!(sigma: self.sigma, model: self.model().as_str(), ...)` in a
/// [`Registered`] impl: [`Registered::values`], each parameter's effective value (anything
/// [`ParamValue`] converts from) given by name, in any order, returned in the SPEC's order. A
/// name the SPEC does not declare, and a parameter left out or named twice, do not compile.
macro_rules! parameter_values {
    ($($name:ident: $value:expr),* $(,)?) => {{
        use $crate::registry::{Registered, names_all_parameters};
        const {
            assert!(
                names_all_parameters(&<Self as Registered>::SPEC, &[$(stringify!($name)),*]),
                "parameter_values! names each parameter of the SPEC once"
            )
        };
        #[allow(unused_mut)]
        let mut values = vec![$crate::ParamValue::Number(0.0); <Self as Registered>::SPEC.params.len()];
        $(values[const { $crate::registry::index_of(&<Self as Registered>::SPEC, stringify!($name)) }] = $crate::ParamValue::from($value);)*
        values
    }};
}
pub(crate) use parameter_values;

/// Which kernel the constants are for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evaluation {
    /// The model's own parameter values, fixed for the call (van Ginneken: the tables of its
    /// roughness, [`Registered::tables`]).
    Constant,
    /// Parameters that vary per lane (textures, `docs/models.md#spatially-varying-parameters`;
    /// van Ginneken: the tables stacked over the roughness).
    Lane,
}

/// Whether the numeric parameters carry gradients the constants must keep (the traced
/// plugin's differentiable parameters).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gradients {
    Needed,
    NotNeeded,
}

/// Named values in any `T` (a model's numeric parameters, its kernel constants) that are flat
/// data only at the boundary that needs it: the traced plugin's arena indices, a texture's
/// per-lane values. The slice order is the declaration order. [`flat_values!`] declares one.
pub trait Flat<T: Copy>: Copy {
    /// The names, in the slice order.
    const NAMES: &'static [&'static str];

    /// The values from the first entries of `c`; `None` if it is short.
    fn from_flat(c: &[T]) -> Option<Self>;

    /// The values in the slice order.
    fn to_flat(&self) -> Vec<T>;

    /// Each value replaced by `f(k, value)`, `k` its position in the slice order.
    #[must_use]
    fn map(self, f: impl FnMut(usize, T) -> T) -> Self;
}

/// No values: the numeric parameters and constants of a model that has none.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoValues;

impl<T: Copy> Flat<T> for NoValues {
    const NAMES: &'static [&'static str] = &[];
    fn from_flat(_: &[T]) -> Option<Self> {
        Some(NoValues)
    }
    fn to_flat(&self) -> Vec<T> {
        Vec::new()
    }
    fn map(self, _: impl FnMut(usize, T) -> T) -> Self {
        self
    }
}

/// `flat_values! { /// doc\n pub struct Name { /// doc\n a, b } }`: a struct of named values
/// `pub a: T, pub b: T` with [`Flat`] (slice order: the fields') and `map_values`, the same
/// values converted to another type.
macro_rules! flat_values {
    ($(#[$m:meta])* $vis:vis struct $name:ident { $($(#[$fm:meta])* $field:ident),+ $(,)? }) => {
        $(#[$m])*
        #[derive(Clone, Copy, Debug, PartialEq)]
        $vis struct $name<T> {
            $($(#[$fm])* pub $field: T,)+
        }

        impl<T: Copy> $crate::registry::Flat<T> for $name<T> {
            const NAMES: &'static [&'static str] = &[$(stringify!($field)),+];

            #[inline(always)]
            fn from_flat(c: &[T]) -> Option<Self> {
                let mut c = c.iter().copied();
                Some(Self { $($field: c.next()?,)+ })
            }

            fn to_flat(&self) -> Vec<T> {
                vec![$(self.$field),+]
            }

            #[inline(always)]
            fn map(self, mut f: impl FnMut(usize, T) -> T) -> Self {
                let mut k = 0;
                $(let $field = f(k, self.$field);
                k += 1;)+
                let _ = k;
                Self { $($field),+ }
            }
        }

        impl<T: Copy> $name<T> {
            /// The same values converted by `f` (f64 constants rounded to f32).
            #[inline(always)]
            pub fn map_values<U>(self, f: impl Fn(T) -> U) -> $name<U> {
                $name { $($field: f(self.$field)),+ }
            }
        }
    };
}
pub(crate) use flat_values;

/// What a model implements to be registered; everything else about it is derived. `T` in the
/// kernel methods is any [`Real`]: f32 and f64 on the CPU, `F32x8`, and the plugin's traced
/// Dr.Jit values (`matte_plugin::traced`), so one implementation serves all of them.
pub trait Registered: KernelBrdf + Clone + Debug + PartialEq + Sized + 'static {
    const SPEC: ModelSpec;

    /// The model's kernel with its constants in `T`, built by [`Self::kernel_from`].
    type Lane<'t, T: Real + 't>: Kernel<T> + Copy;

    /// The model from its parameters (defaults filled in, ranges checked). Checks that
    /// involve several parameters (Wolff: int_ior ≥ ext_ior) are made here.
    fn build(values: &Values) -> Result<Self, ParamError>;

    /// The effective value of every parameter, in the SPEC's order (numbers as the model
    /// stores them, words and flags as text): [`parameter_values!`].
    fn values(&self) -> Vec<ParamValue>;

    /// The numeric parameters by name ([`flat_values!`], or [`NoValues`]), in the order of
    /// [`ModelSpec::numeric`] (checked at compile time): the values a texture or the traced
    /// plugin gives.
    type Parameters<T: Real>: Flat<T>;

    /// The kernel's constants by name ([`flat_values!`], or [`NoValues`]).
    type Coefficients<T: Real>: Flat<T>;

    /// The kernel constants for numeric parameter values in `T`, as the traced plugin computes
    /// them once per parameter change (with the parameters' gradients if `gradients` says so).
    fn constant_coefficients<T: Real>(&self, p: Self::Parameters<T>, gradients: Gradients) -> Self::Coefficients<T>;

    /// The kernel constants for per-lane (textured) values, each clamped into its lane clamp
    /// first (`docs/models.md#spatially-varying-parameters`). Default: clamp, then
    /// [`Self::constant_coefficients`] with gradients.
    #[inline(always)]
    fn lane_coefficients<T: Real>(&self, p: Self::Parameters<T>) -> Self::Coefficients<T> {
        self.constant_coefficients(clamp_lanes::<Self, T>(p), Gradients::Needed)
    }

    /// The kernel from constants `c` (of either coefficient method) and the tables
    /// ([`Self::tables`] of the same `evaluation`) in `T`'s table type. `None` if `tables` is
    /// short.
    fn kernel_from<'t, T: Real + 't>(
        &'t self,
        c: Self::Coefficients<T>,
        tables: &[T::Table<'t>],
        evaluation: Evaluation,
    ) -> Option<Self::Lane<'t, T>>;

    /// Tables the kernel reads (van Ginneken's slope integral and its derivative at its
    /// roughness, or for [`Evaluation::Lane`] stacked over the roughness; `tabulated_brdf`'s
    /// values); the plugin registers them as Dr.Jit arrays.
    fn tables(&self, evaluation: Evaluation) -> Vec<&[f32]> {
        let _ = evaluation;
        Vec::new()
    }

    /// The number a textured parameter `name` stands for when the model is built and
    /// validated as a number: the texture's `mean` clamped into the lane clamp. `number`
    /// gives another parameter's value when it is a number (Wolff's indices bound each other).
    fn placeholder(name: &str, mean: f64, number: &dyn Fn(&str) -> Option<f64>) -> f64 {
        let _ = number;
        Self::SPEC.param(name).map_or(mean, |p| p.clamp_lane(mean))
    }
}

/// The numeric parameters `p` of model `M`, each clamped into its lane clamp (NaN to the
/// lower bound).
#[inline(always)]
pub fn clamp_lanes<M: Registered, T: Real>(p: M::Parameters<T>) -> M::Parameters<T> {
    p.map(|k, x| {
        let Some(spec) = M::SPEC.numeric().nth(k) else { return x };
        let (lo, hi) = spec.lane_clamp;
        let x = if lo > f64::NEG_INFINITY { x.max(T::c(lo)) } else { x };
        if hi < f64::INFINITY { x.min(T::c(hi)) } else { x }
    })
}

/// `models! { Variant: module::Type, ... }`: declares the model modules and generates
/// everything that lists the models (see the module comment). The order is the README's.
macro_rules! models {
    ($($variant:ident : $module:ident :: $ty:ident),+ $(,)?) => {
        $crate::registry::models!(@with_dollar ($) $($variant : $module :: $ty),+);
    };
    (@with_dollar ($d:tt) $($variant:ident : $module:ident :: $ty:ident),+) => {
        $(pub mod $module;)+
        $(pub use $module::$ty;)+

        /// Every registered model's declaration, in the README's order.
        pub const MODELS: &[&$crate::registry::ModelSpec] =
            &[$(&<$ty as $crate::registry::Registered>::SPEC),+];

        /// The plugin names, in the README's order.
        pub const BSDF_TYPES: &[&str] = &[$(<$ty as $crate::registry::Registered>::SPEC.name),+];

        const _: () = {
            $(assert!(
                $crate::registry::numeric_count(&<$ty as $crate::registry::Registered>::SPEC)
                    <= $crate::registry::MAX_NUMERIC,
                "a model has more numeric parameters than MAX_NUMERIC"
            );
            assert!(
                $crate::registry::names_numeric_parameters(
                    &<$ty as $crate::registry::Registered>::SPEC,
                    <<$ty as $crate::registry::Registered>::Parameters<f32> as $crate::registry::Flat<f32>>::NAMES,
                ),
                "a model's Parameters are not its SPEC's numeric parameters, in order"
            );
            assert!(
                $crate::registry::fits_are_valid(&<$ty as $crate::registry::Registered>::SPEC),
                "a model's fit bounds lie outside its range or lane clamp (declare them with `with_fit`)"
            );)+
        };

        /// One of matte's diffuse models with its (validated) parameters.
        #[derive(Clone, Debug, PartialEq)]
        pub enum DiffuseModel {
            $($variant($ty),)+
        }

        /// One model's kernel with constants in `T` (per-lane or traced parameters).
        #[derive(Clone, Copy)]
        pub enum LaneKernel<'t, T: $crate::real::Real + 't> {
            $($variant(<$ty as $crate::registry::Registered>::Lane<'t, T>),)+
        }

        impl<'t, T: $crate::real::Real + 't> $crate::kernel::Kernel<T> for LaneKernel<'t, T> {
            #[inline(always)]
            fn reduced_f<const N: usize>(
                &self,
                wi: $crate::real::V3<T>,
                wo: $crate::real::V3<T>,
                rho: [T; N],
            ) -> [T; N] {
                match self {
                    $(LaneKernel::$variant(k) => k.reduced_f(wi, wo, rho),)+
                }
            }

            #[inline(always)]
            fn cosine_sampling(&self) -> bool {
                match self {
                    $(LaneKernel::$variant(k) => $crate::kernel::Kernel::<T>::cosine_sampling(k),)+
                }
            }

            #[inline(always)]
            fn sample_wo(
                &self,
                wi: $crate::real::V3<T>,
                u1: T,
                u2: T,
            ) -> ($crate::real::V3<T>, T) {
                match self {
                    $(LaneKernel::$variant(k) => k.sample_wo(wi, u1, u2),)+
                }
            }

            #[inline(always)]
            fn pdf_wo(&self, wi: $crate::real::V3<T>, wo: $crate::real::V3<T>) -> T {
                match self {
                    $(LaneKernel::$variant(k) => k.pdf_wo(wi, wo),)+
                }
            }
        }

        /// `dispatch!(model, m => expr)`: evaluates `expr` with `m` bound to the concrete
        /// model (static dispatch); `dispatch!(model, m => expr, lane)` also wraps the
        /// expression's `Option<Lane>` into a [`LaneKernel`] of the same variant.
        macro_rules! dispatch {
            ($d self_:expr, $d b:ident => $d e:expr) => {
                match $d self_ {
                    $($crate::DiffuseModel::$variant($d b) => $d e,)+
                }
            };
            ($d self_:expr, $d b:ident => $d e:expr, lane) => {
                match $d self_ {
                    $($crate::DiffuseModel::$variant($d b) => ($d e).map($crate::LaneKernel::$variant),)+
                }
            };
        }
        pub(crate) use dispatch;

        impl DiffuseModel {
            /// Builds the model `kind` (a plugin name) from its parameters. `reflectance` is
            /// not a model parameter here: it is per channel and per call (textures). Unknown
            /// names, unknown parameters and out-of-range values are errors naming the
            /// parameter.
            pub fn from_params(kind: &str, mut params: $crate::Params) -> Result<Self, $crate::ParamError> {
                use $crate::registry::{Registered, Values};
                $(
                    if kind == <$ty as Registered>::SPEC.name {
                        let spec = &<$ty as Registered>::SPEC;
                        let model = <$ty>::build(&Values::read(spec, &mut params)?)?;
                        params.finish(kind, &spec.names())?;
                        return Ok(DiffuseModel::$variant(model));
                    }
                )+
                Err($crate::ParamError::new(
                    "type",
                    format!("unknown bsdf type \"{kind}\" (known: {})", BSDF_TYPES.join(", ")),
                ))
            }

            /// The model's declaration.
            pub fn spec(&self) -> &'static $crate::registry::ModelSpec {
                match self {
                    $(DiffuseModel::$variant(_) => &<$ty as $crate::registry::Registered>::SPEC,)+
                }
            }
        }

        /// The declaration of the model `kind` (a plugin name).
        pub fn spec(kind: &str) -> Option<&'static $crate::registry::ModelSpec> {
            MODELS.iter().copied().find(|s| s.name == kind)
        }

        /// [`$crate::registry::Registered::placeholder`] of the model `kind`; `mean`
        /// itself for unknown kinds.
        pub fn placeholder(kind: &str, name: &str, mean: f64, number: &dyn Fn(&str) -> Option<f64>) -> f64 {
            use $crate::registry::Registered;
            $(
                if kind == <$ty as Registered>::SPEC.name {
                    return <$ty>::placeholder(name, mean, number);
                }
            )+
            mean
        }
    };
}
pub(crate) use models;

/// A BRDF given by an f32 [`Kernel`]: every registered model, and matte's tabulated BRDF
/// (`super::tabulated::Tabulated`). Each is a [`DiffuseBrdf`] through the blanket
/// implementation below.
pub trait KernelBrdf {
    /// The kernel in f32 with its constants: what every [`DiffuseBrdf`] method runs.
    fn f32_kernel(&self) -> impl Kernel<f32> + '_;

    /// The directional albedo for a grey reflectance `rho` in closed form, where the model has
    /// one; `None` (the default) lets [`DiffuseBrdf::albedo`] integrate numerically. Called
    /// with `cos_theta_i > 0` only (the albedo is 0 below the surface).
    fn closed_form_albedo(&self, cos_theta_i: f64, rho: f32) -> Option<f64> {
        let _ = (cos_theta_i, rho);
        None
    }
}

/// Every [`KernelBrdf`] is a [`DiffuseBrdf`] through its f32 kernel: evaluation, density and
/// sampling are [`kernel`]'s, the albedo the model's closed form or quadrature.
impl<M: KernelBrdf> DiffuseBrdf for M {
    /// `inline(always)`: with the full Oren–Nayar body the function exceeds the inliner's
    /// threshold, and a call would cost the default (qualitative) model a third of its time.
    #[inline(always)]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        kernel::eval(&self.f32_kernel(), wi.into(), wo.into(), reflectance)
    }

    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        kernel::pdf(&self.f32_kernel(), wi.into(), wo.into())
    }

    #[inline]
    fn sample<const N: usize>(&self, wi: Vec3, u: Vec2, reflectance: [f32; N]) -> Option<BrdfSample<N>> {
        BrdfSample::from_kernel(kernel::sample(&self.f32_kernel(), wi.into(), u.x, u.y, reflectance))
    }

    fn albedo(&self, cos_theta_i: f64, reflectance: f32) -> Albedo {
        if cos_theta_i <= 0.0 {
            return Albedo { value: 0.0, method: AlbedoMethod::ClosedForm };
        }
        match self.closed_form_albedo(cos_theta_i, reflectance) {
            Some(value) => Albedo { value, method: AlbedoMethod::ClosedForm },
            None => {
                Albedo { value: albedo_by_quadrature(self, cos_theta_i, reflectance), method: AlbedoMethod::Quadrature }
            }
        }
    }
}
