//! `$name` parameters: `-D` overrides, `<default>` and the plain-text substitution Mitsuba
//! applies to every attribute value (`src/core/parser.cpp::substitute_parameters`,
//! `make_sorted_parameters`, `TagType::Default`; docs/renderer-semantics.md §1 "Parameters").

use crate::error::{SceneError, SourcePos};

struct Param {
    /// The search key, `$` included.
    key: String,
    value: String,
    used: bool,
}

/// The parameters in effect, longest key first so that `$rr` is replaced before `$r`
/// (equal lengths keep their definition order). Shared by a file and all its includes.
pub(crate) struct Substitutions {
    list: Vec<Param>,
}

impl Substitutions {
    /// The `-D key=value` overrides; each must be used somewhere ([`Substitutions::check_all_used`]).
    pub(crate) fn new(overrides: &[(String, String)]) -> Self {
        let mut p = Substitutions { list: Vec::with_capacity(overrides.len()) };
        for (k, v) in overrides {
            p.insert(k, v, false);
        }
        p
    }

    fn insert(&mut self, name: &str, value: &str, used: bool) {
        let key = format!("${name}");
        // Before the first strictly shorter key: a stable longest-first order.
        let at = self.list.iter().position(|q| q.key.len() < key.len()).unwrap_or(self.list.len());
        self.list.insert(at, Param { key, value: value.to_string(), used });
    }

    /// `<default name value>`: defines `name` unless an override or an earlier default did.
    /// Defaults are never reported as unused.
    pub(crate) fn add_default(&mut self, name: &str, value: &str) {
        if !self.list.iter().any(|q| &q.key[1..] == name) {
            self.insert(name, value, true);
        }
    }

    /// Replaces every parameter in `value`: plain text, no word boundary (`$r5` with r=0.2 is
    /// `0.25`), `\$` protects a dollar. A `$` left over afterwards names an undefined parameter.
    pub(crate) fn substitute(&mut self, value: &str, pos: &SourcePos) -> Result<String, SceneError> {
        if !value.contains('$') {
            return Ok(value.to_string());
        }
        let mut s = value.to_string();
        for p in &mut self.list {
            let mut from = 0;
            while let Some(off) = s[from..].find(&p.key) {
                let at = from + off;
                if at > 0 && s.as_bytes()[at - 1] == b'\\' {
                    from = at + p.key.len();
                } else {
                    s.replace_range(at..at + p.key.len(), &p.value);
                    p.used = true;
                    from = at + p.value.len();
                }
            }
        }
        let bytes = s.as_bytes();
        for (i, _) in s.match_indices('$') {
            if i > 0 && bytes[i - 1] == b'\\' {
                continue;
            }
            let name: String = s[i + 1..].chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
            return Err(SceneError::at(
                pos,
                format!("undefined parameter ${name} (define it with -D {name}=... or a <default> before this line)"),
            ));
        }
        Ok(s.replace("\\$", "$"))
    }

    /// Mitsuba treats an override that nothing used as an error
    /// (`ParserConfig::unused_parameters = Error`): it is almost always a typo.
    pub(crate) fn check_all_used(&self, file: &SourcePos) -> Result<(), SceneError> {
        let unused: Vec<String> =
            self.list.iter().filter(|p| !p.used).map(|p| format!("{}={}", p.key, p.value)).collect();
        match unused.len() {
            0 => Ok(()),
            1 => Err(SceneError::at(file, format!("unused parameter {}", unused[0]))),
            _ => Err(SceneError::at(file, format!("unused parameters {}", unused.join(", ")))),
        }
    }
}
