//! Typed properties of one scene object, with Mitsuba's conversion rules and its
//! "every property must be queried" check (`include/mitsuba/core/properties.h::get`,
//! `src/core/properties.cpp`, `src/core/parser.cpp::instantiate_node`; docs/renderer-semantics.md §1–2).

use std::cell::Cell;

use glam::{DMat4, DVec3};

use super::color::{ColorUse, constant_spectrum_rgb, sampled_spectrum_rgb};
use crate::error::{SceneError, SourcePos};

/// A spectrum property (`<spectrum value=...>`).
#[derive(Clone, Debug, PartialEq)]
pub enum Spectrum {
    /// One number: the same value at every wavelength.
    Constant(f64),
    /// (λ in nm, value) pairs, wavelengths strictly increasing, at least two.
    Sampled(Vec<(f64, f64)>),
}

/// The value of a property tag, numbers kept in f64 as Mitsuba's parser does (§0).
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Integer(i64),
    Float(f64),
    Boolean(bool),
    String(String),
    Rgb([f64; 3]),
    Spectrum(Spectrum),
    Point(DVec3),
    Vector(DVec3),
    Transform(DMat4),
}

impl Value {
    /// The XML tag that produces this value, used in messages.
    pub fn type_name(&self) -> &'static str {
        match self {
            Value::Integer(_) => "integer",
            Value::Float(_) => "float",
            Value::Boolean(_) => "boolean",
            Value::String(_) => "string",
            Value::Rgb(_) => "rgb",
            Value::Spectrum(_) => "spectrum",
            Value::Point(_) => "point",
            Value::Vector(_) => "vector",
            Value::Transform(_) => "transform",
        }
    }
}

/// One property: `<float name="alpha" value="0.2"/>` and the like.
#[derive(Debug)]
pub struct Property {
    pub name: String,
    pub value: Value,
    /// Of the property element.
    pub pos: SourcePos,
    /// Set by every getter; [`Properties::check_all_used`] reports the ones never queried.
    pub used: Cell<bool>,
}

/// The properties of one object, in document order; names are unique.
#[derive(Debug, Default)]
pub struct Properties {
    list: Vec<Property>,
}

impl Properties {
    pub(crate) fn push(&mut self, p: Property) {
        self.list.push(p);
    }

    pub(crate) fn find_mut(&mut self, name: &str) -> Option<&mut Property> {
        self.list.iter_mut().find(|p| p.name == name)
    }

    pub(crate) fn remove(&mut self, name: &str) -> Option<Property> {
        let i = self.list.iter().position(|p| p.name == name)?;
        Some(self.list.remove(i))
    }

    pub fn len(&self) -> usize {
        self.list.len()
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Whether `name` is present; does not mark it used.
    pub fn contains(&self, name: &str) -> bool {
        self.list.iter().any(|p| p.name == name)
    }

    /// Raw access; marks the property used.
    pub fn get(&self, name: &str) -> Option<&Property> {
        let p = self.list.iter().find(|p| p.name == name)?;
        p.used.set(true);
        Some(p)
    }

    /// All properties in document order (does not mark them used).
    pub fn iter(&self) -> impl Iterator<Item = &Property> {
        self.list.iter()
    }

    /// Looks `name` up, marks it used and converts it with `convert`; `None` from `convert`
    /// is a type error naming the expected and the found type.
    fn typed<T>(
        &self,
        name: &str,
        expected: &str,
        convert: impl FnOnce(&Value) -> Option<T>,
    ) -> Result<Option<T>, SceneError> {
        let Some(p) = self.get(name) else { return Ok(None) };
        match convert(&p.value) {
            Some(v) => Ok(Some(v)),
            None => Err(SceneError::at(
                &p.pos,
                format!("property \"{name}\" has the wrong type (expected {expected}, found {})", p.value.type_name()),
            )),
        }
    }

    /// A float; an integer is accepted too (Mitsuba converts int → float, never the reverse).
    pub fn float(&self, name: &str) -> Result<Option<f64>, SceneError> {
        self.typed(name, "float", |v| match *v {
            Value::Float(x) => Some(x),
            Value::Integer(i) => Some(i as f64),
            _ => None,
        })
    }

    pub fn integer(&self, name: &str) -> Result<Option<i64>, SceneError> {
        self.typed(name, "integer", |v| match *v {
            Value::Integer(i) => Some(i),
            _ => None,
        })
    }

    pub fn boolean(&self, name: &str) -> Result<Option<bool>, SceneError> {
        self.typed(name, "boolean", |v| match *v {
            Value::Boolean(b) => Some(b),
            _ => None,
        })
    }

    pub fn string(&self, name: &str) -> Result<Option<String>, SceneError> {
        self.typed(name, "string", |v| match v {
            Value::String(s) => Some(s.clone()),
            _ => None,
        })
    }

    /// A `<point>`, or a `<vector>`: Mitsuba 3 stores both as one 3-vector type.
    pub fn point(&self, name: &str) -> Result<Option<DVec3>, SceneError> {
        self.typed(name, "point", |v| match *v {
            Value::Point(p) | Value::Vector(p) => Some(p),
            _ => None,
        })
    }

    /// A `<vector>`, or a `<point>` (see [`Properties::point`]).
    pub fn vector(&self, name: &str) -> Result<Option<DVec3>, SceneError> {
        self.typed(name, "vector", |v| match *v {
            Value::Point(p) | Value::Vector(p) => Some(p),
            _ => None,
        })
    }

    pub fn transform(&self, name: &str) -> Result<Option<DMat4>, SceneError> {
        self.typed(name, "transform", |v| match *v {
            Value::Transform(m) => Some(m),
            _ => None,
        })
    }

    /// A constant colour as linear RGB, read the way `usage` demands (docs/renderer-semantics.md §2):
    /// `<float>`/`<integer>` v → (v,v,v); `<rgb>` as is, but a [`ColorUse::Bounded`] channel
    /// outside [0, 1] is an error; `<spectrum value="v">` → (v,v,v), or
    /// v·(1.204794, 0.948291, 0.908916) when [`ColorUse::Emissive`]; a sampled spectrum is
    /// integrated against CIE 1931 ([`super::spectrum_list_to_srgb`]). A nested texture is a
    /// child object, not a property: look for it with [`super::SceneObject::child`].
    pub fn color(&self, name: &str, usage: ColorUse) -> Result<Option<[f64; 3]>, SceneError> {
        let Some(p) = self.get(name) else { return Ok(None) };
        let rgb = match &p.value {
            Value::Integer(i) => [*i as f64; 3],
            Value::Float(x) => [*x; 3],
            Value::Rgb(c) => {
                // Mitsuba checks after narrowing to float (`srgb.cpp`): 1.0000000001 passes.
                if usage == ColorUse::Bounded && !c.iter().all(|&v| (0.0..=1.0).contains(&(v as f32))) {
                    return Err(SceneError::at(
                        &p.pos,
                        format!(
                            "invalid RGB reflectance value ({}, {}, {}) for \"{name}\": each channel must be in [0, 1]",
                            c[0], c[1], c[2]
                        ),
                    ));
                }
                *c
            }
            Value::Spectrum(Spectrum::Constant(v)) => constant_spectrum_rgb(*v, usage),
            Value::Spectrum(Spectrum::Sampled(s)) => sampled_spectrum_rgb(s, usage),
            other => {
                return Err(SceneError::at(
                    &p.pos,
                    format!(
                        "property \"{name}\" has the wrong type (expected rgb, spectrum, float or a texture, found {})",
                        other.type_name()
                    ),
                ));
            }
        };
        Ok(Some(rgb))
    }

    /// Error for the first property never queried, worded like Mitsuba's
    /// (`ParserConfig::unused_properties = Error`): a misspelt or unsupported parameter must
    /// not silently render a different picture.
    pub fn check_all_used(&self, tag: &str, plugin: &str) -> Result<(), SceneError> {
        match self.list.iter().find(|p| !p.used.get()) {
            None => Ok(()),
            Some(p) => Err(SceneError::at(
                &p.pos,
                format!(
                    "unreferenced property \"{}\" ({}) in {tag} plugin of type \"{plugin}\"",
                    p.name,
                    p.value.type_name()
                ),
            )),
        }
    }
}
