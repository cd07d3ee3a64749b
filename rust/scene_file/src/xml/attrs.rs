//! One XML element's attributes after `$` substitution, with the checks and value readers
//! every tag shares (`src/core/parser.cpp::check_attributes`, `expand_value_to_xyz`,
//! `parse_vector`, `parse_vector_from_string`). Every error names the element's position.

use glam::DVec3;

use super::numbers::{parse_f64, tokenize};
use crate::error::{SceneError, SourcePos};

pub(crate) struct Attrs {
    pub tag: String,
    pub pos: SourcePos,
    list: Vec<(String, String)>,
}

impl Attrs {
    pub(crate) fn new(tag: &str, pos: SourcePos, list: Vec<(String, String)>) -> Self {
        Attrs { tag: tag.to_string(), pos, list }
    }

    pub(crate) fn err(&self, message: impl Into<String>) -> SceneError {
        SceneError::at(&self.pos, message)
    }

    pub(crate) fn get(&self, name: &str) -> Option<&str> {
        self.list.iter().find(|(k, _)| k == name).map(|(_, v)| v.as_str())
    }

    /// The attribute, or an error naming it.
    pub(crate) fn required(&self, name: &str) -> Result<&str, SceneError> {
        self.get(name).ok_or_else(|| self.err(format!("missing required attribute \"{name}\" in <{}>", self.tag)))
    }

    /// Every attribute must be in `allowed` (required ones prefixed with `!`), and every
    /// required one must be present: an attribute matte would silently ignore is an error.
    pub(crate) fn check(&self, allowed: &[&str]) -> Result<(), SceneError> {
        for (k, _) in &self.list {
            if !allowed.iter().any(|a| a.trim_start_matches('!') == k) {
                return Err(self.err(format!("unexpected attribute \"{k}\" in <{}>", self.tag)));
            }
        }
        for a in allowed.iter().filter_map(|a| a.strip_prefix('!')) {
            self.required(a)?;
        }
        Ok(())
    }

    pub(crate) fn float_value(&self, what: &str, s: &str) -> Result<f64, SceneError> {
        parse_f64(s).ok_or_else(|| {
            self.err(format!("could not parse {what} \"{s}\" in <{}> as a floating point number", self.tag))
        })
    }

    /// `value="a"` or `value="a b c"` expanded into x, y, z (Mitsuba's `expand_value_to_xyz`);
    /// mixing `value` with x/y/z is an error.
    pub(crate) fn expand_value_to_xyz(&mut self) -> Result<(), SceneError> {
        let Some(idx) = self.list.iter().position(|(k, _)| k == "value") else { return Ok(()) };
        if ["x", "y", "z"].iter().any(|c| self.get(c).is_some()) {
            return Err(self.err(format!("<{}> cannot mix \"value\" with \"x\"/\"y\"/\"z\"", self.tag)));
        }
        let (_, value) = self.list.remove(idx);
        let tokens: Vec<String> = tokenize(&value).into_iter().map(str::to_string).collect();
        let xyz = match tokens.len() {
            1 => [tokens[0].clone(), tokens[0].clone(), tokens[0].clone()],
            3 => [tokens[0].clone(), tokens[1].clone(), tokens[2].clone()],
            n => {
                return Err(
                    self.err(format!("\"value\" of <{}> must have 1 or 3 numbers, got {n} (\"{value}\")", self.tag))
                );
            }
        };
        for (k, v) in ["x", "y", "z"].into_iter().zip(xyz) {
            self.list.push((k.to_string(), v));
        }
        Ok(())
    }

    /// x, y, z attributes, each `default` when absent (Mitsuba's `parse_vector`).
    pub(crate) fn xyz(&self, default: f64) -> Result<DVec3, SceneError> {
        let mut v = [default; 3];
        for (c, out) in ["x", "y", "z"].iter().zip(v.iter_mut()) {
            if let Some(s) = self.get(c) {
                *out = self.float_value(c, s)?;
            }
        }
        Ok(DVec3::from_array(v))
    }

    /// Exactly three numbers separated by spaces and/or commas (`lookat` origin/target/up).
    pub(crate) fn vec3_attr(&self, name: &str) -> Result<DVec3, SceneError> {
        let s = self.required(name)?;
        let tokens = tokenize(s);
        if tokens.len() != 3 {
            return Err(self.err(format!(
                "\"{name}\" of <{}> must have 3 numbers, got {} (\"{s}\")",
                self.tag,
                tokens.len()
            )));
        }
        let mut v = [0.0; 3];
        for (t, out) in tokens.iter().zip(v.iter_mut()) {
            *out = self.float_value(name, t)?;
        }
        Ok(DVec3::from_array(v))
    }
}
