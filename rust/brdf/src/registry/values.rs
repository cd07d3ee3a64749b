//! A model's parameters as its `build` reads them: [`Values`], every parameter of the SPEC
//! read from the given [`Params`] (defaults filled in, ranges checked), by [`Param`]s checked
//! against the SPEC at compile time ([`param!`]); and [`parameter_values!`], the effective
//! values a model reports.

use super::spec::{ModelSpec, ParamKind};
use crate::params::{ParamError, ParamValue, Params};

/// A model's parameters read from [`Params`] by its [`ModelSpec`]: every parameter present
/// (defaults filled in), numbers range-checked, a choice as the SPEC spells it.
/// [`Registered::build`](super::registered::Registered::build) takes them by [`Param`].
#[derive(Clone, Debug)]
pub struct Values {
    spec: &'static ModelSpec,
    values: Vec<ParamValue>,
}

impl Values {
    /// Reads every parameter of `spec` from `params` (marking them used; unknown names are
    /// left for [`Params::finish`]).
    pub fn read(spec: &'static ModelSpec, params: &mut Params) -> Result<Self, ParamError> {
        let mut values = Vec::with_capacity(spec.params.len());
        for p in spec.params {
            values.push(match p.kind {
                ParamKind::Number { default } => ParamValue::Number(p.check(params.number(p.name, default)?)?),
                ParamKind::Ior { default } => ParamValue::Number(p.check(params.ior(p.name, default)?)?),
                ParamKind::Choice { choices, default } => {
                    ParamValue::Text(params.choice(p.name, choices, default)?.to_string())
                }
                ParamKind::Flag { default } => ParamValue::Flag(params.flag(p.name, default)?),
                ParamKind::File => ParamValue::Text(params.file(p.name)?),
            });
        }
        Ok(Self { spec, values })
    }

    fn get<K>(&self, p: Param<K>) -> &ParamValue {
        &self.values[p.index]
    }

    /// A number or an index of refraction.
    pub fn number(&self, p: Param<kind::Number>) -> f64 {
        match self.get(p) {
            ParamValue::Number(x) => *x,
            _ => unreachable!("Param::of checked the kind"),
        }
    }

    /// A choice, as the SPEC spells it.
    pub fn choice(&self, p: Param<kind::Choice>) -> &'static str {
        let (ParamKind::Choice { choices, .. }, ParamValue::Text(given)) =
            (&self.spec.params[p.index].kind, self.get(p))
        else {
            unreachable!("Param::of checked the kind")
        };
        choices.iter().copied().find(|c| c == given).expect("Params::choice returned one of the choices")
    }

    /// A boolean.
    pub fn flag(&self, p: Param<kind::Flag>) -> bool {
        match self.get(p) {
            ParamValue::Flag(b) => *b,
            _ => unreachable!("Param::of checked the kind"),
        }
    }

    /// A file parameter's name (resolved by the front end).
    pub fn file(&self, p: Param<kind::File>) -> &str {
        match self.get(p) {
            ParamValue::Text(f) => f,
            _ => unreachable!("Param::of checked the kind"),
        }
    }
}

/// The kinds a [`Param`] is read as: one [`Values`] accessor each.
pub mod kind {
    use crate::registry::spec::ParamKind;

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
