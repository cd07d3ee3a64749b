//! Which PLY properties become mesh attributes, and under which name: Mitsuba's
//! `find_other_fields` (`src/shapes/ply.h`, v3.9.1), applied to the vertex and the face
//! element.
//!
//! * `r g b` (or `red green blue`, renamed), with an optional `a`/`alpha`, become
//!   `<element>_color` (3 or 4 floats).
//! * Every other property that is not reserved is `prefix_postfix` with a one-letter postfix;
//!   consecutive properties with the same prefix and postfixes in one of the sequences
//!   `x y z w`, `r g b a`, `0 1 2 3`, `1 2 3 4` form one attribute named
//!   `<element>_prefix` (`<element>_prefix_color` for `r g b a`). Only 1 or 3 fields are
//!   kept; a prefix seen before, a broken sequence, a name without `_` or with a longer
//!   postfix is skipped (Mitsuba warns).

/// One attribute: its Mitsuba name and the PLY properties it reads, in order.
#[derive(Clone, Debug, PartialEq)]
pub struct AttributeFields {
    pub name: String,
    pub fields: Vec<String>,
}

const POSTFIXES: [&[u8; 4]; 4] = [b"xr01", b"yg12", b"zb23", b"wa34"];

/// The attributes of one element (`element` is "vertex" or "face"), given its property names
/// in file order and the names the loader reads itself.
pub fn find_attributes(element: &str, properties: &[String], reserved: &[&str]) -> Vec<AttributeFields> {
    let has = |n: &str| properties.iter().any(|p| p == n);
    let mut out = Vec::new();
    let mut reserved: Vec<String> = reserved.iter().map(|s| s.to_string()).collect();
    let colour = if has("r") && has("g") && has("b") {
        Some(["r", "g", "b", "a"])
    } else if has("red") && has("green") && has("blue") {
        Some(["red", "green", "blue", "alpha"])
    } else {
        None
    };
    if let Some(names) = colour {
        let mut fields: Vec<String> = names[..3].iter().map(|s| s.to_string()).collect();
        if has(names[3]) {
            fields.push(names[3].to_string());
        }
        reserved.extend(fields.iter().cloned());
        out.push(AttributeFields { name: format!("{element}_color"), fields });
    }
    reserved.extend(["r", "g", "b", "a"].map(String::from));

    struct Current {
        prefix: String,
        category: usize,
        fields: Vec<String>,
    }
    let mut seen: Vec<String> = Vec::new();
    let mut current: Option<Current> = None;
    let flush = |c: Current, out: &mut Vec<AttributeFields>, seen: &mut Vec<String>| {
        if c.fields.len() == 1 || c.fields.len() == 3 {
            let suffix = if c.category == 1 { "_color" } else { "" };
            out.push(AttributeFields { name: format!("{element}_{}{suffix}", c.prefix), fields: c.fields });
            seen.push(c.prefix);
        }
    };
    let mut skip_prefix: Option<String> = None;
    for p in properties {
        if reserved.iter().any(|r| r == p) {
            continue;
        }
        if let Some(sp) = &skip_prefix {
            if p.starts_with(sp.as_str()) {
                continue;
            }
            skip_prefix = None;
        }
        let Some(pos) = p.rfind('_') else {
            if let Some(c) = current.take() {
                flush(c, &mut out, &mut seen);
            }
            continue;
        };
        let (prefix, postfix) = (&p[..pos], &p[pos + 1..]);
        if postfix.len() != 1 {
            if let Some(c) = current.take() {
                flush(c, &mut out, &mut seen);
            }
            continue;
        }
        if current.as_ref().is_some_and(|c| c.prefix != prefix) {
            flush(current.take().unwrap(), &mut out, &mut seen);
        }
        let ch = postfix.as_bytes()[0];
        match &mut current {
            None => {
                if seen.iter().any(|s| s == prefix) {
                    skip_prefix = Some(prefix.to_string());
                    continue;
                }
                let Some(category) = POSTFIXES[0].iter().position(|&c| c == ch) else { continue };
                current = Some(Current { prefix: prefix.to_string(), category, fields: vec![p.clone()] });
            }
            Some(c) => {
                let level = c.fields.len();
                if level >= 4 || POSTFIXES[level][c.category] != ch {
                    current = None;
                    skip_prefix = Some(prefix.to_string());
                    continue;
                }
                c.fields.push(p.clone());
            }
        }
    }
    if let Some(c) = current.take() {
        flush(c, &mut out, &mut seen);
    }
    out
}
