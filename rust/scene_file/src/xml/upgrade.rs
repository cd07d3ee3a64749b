//! Files with `version` < 2.0.0 (Mitsuba 0.x scenes) are upgraded the way Mitsuba 3 does it
//! (`src/core/parser.cpp::upgrade_from_v1`): camelCase property and child names become
//! snake_case, diffuse's `diffuse_reflectance` becomes `reflectance`, and
//! `uoffset`/`voffset`/`uscale`/`vscale` become a `to_uv` transform.

use glam::{DMat4, DVec3};

use super::properties::{Property, Value};
use super::raw::RawNode;
use crate::error::SceneError;

/// `fooBar` → `foo_bar`; a run of capitals after a lower-case letter is lowered as one word
/// (`intIOR` → `int_ior`), exactly like Mitsuba's `camel_to_underscore_case`.
pub(crate) fn camel_to_snake(s: &str) -> String {
    let c: Vec<char> = s.chars().collect();
    let mut out = String::with_capacity(s.len() + 4);
    let mut i = 0;
    while i < c.len() {
        if i > 0 && c[i - 1].is_ascii_lowercase() && c[i].is_ascii_uppercase() {
            out.push('_');
            out.push(c[i].to_ascii_lowercase());
            while i + 1 < c.len() && c[i + 1].is_ascii_uppercase() {
                i += 1;
                out.push(c[i].to_ascii_lowercase());
            }
        } else {
            out.push(c[i]);
        }
        i += 1;
    }
    out
}

fn rename(node: &mut RawNode, old: &str, new: &str) -> Result<(), SceneError> {
    let taken =
        node.properties.iter().any(|p| p.name == new) || node.children.iter().any(|c| c.name.as_deref() == Some(new));
    if let Some(p) = node.properties.find_mut(old) {
        if taken {
            return Err(SceneError::at(
                &p.pos,
                format!("\"{old}\" becomes \"{new}\" in a version 1 scene, which is already specified"),
            ));
        }
        p.name = new.to_string();
    } else if let Some(c) = node.children.iter_mut().find(|c| c.name.as_deref() == Some(old)) {
        if taken {
            return Err(SceneError::at(
                &c.pos,
                format!("\"{old}\" becomes \"{new}\" in a version 1 scene, which is already specified"),
            ));
        }
        c.name = Some(new.to_string());
    }
    Ok(())
}

/// Upgrades `node` in place if its file is older than 2.0.0.
pub(crate) fn upgrade_v1(node: &mut RawNode) -> Result<(), SceneError> {
    if node.version >= [2, 0, 0] {
        return Ok(());
    }
    let names: Vec<String> = node
        .properties
        .iter()
        .map(|p| p.name.clone())
        .chain(node.children.iter().filter_map(|c| c.name.clone()))
        .collect();
    for old in names {
        let new = camel_to_snake(&old);
        if new != old {
            rename(node, &old, &new)?;
        }
    }
    if node.plugin == "diffuse" {
        rename(node, "diffuse_reflectance", "reflectance")?;
    }
    // [offset, scale]
    let mut uv = [DVec3::ZERO, DVec3::ONE];
    let mut pos = None;
    for (name, which, axis) in [("uoffset", 0, 0), ("voffset", 0, 1), ("uscale", 1, 0), ("vscale", 1, 1)] {
        let Some(p) = node.properties.remove(name) else { continue };
        uv[which][axis] = match p.value {
            Value::Float(x) => x,
            Value::Integer(i) => i as f64,
            ref v => {
                return Err(SceneError::at(
                    &p.pos,
                    format!("property \"{name}\" has the wrong type (expected float, found {})", v.type_name()),
                ));
            }
        };
        pos.get_or_insert(p.pos);
    }
    if let Some(pos) = pos {
        if node.properties.iter().any(|p| p.name == "to_uv") {
            return Err(SceneError::at(&pos, "uoffset/voffset/uscale/vscale conflict with an explicit to_uv"));
        }
        let m = DMat4::from_scale(uv[1]) * DMat4::from_translation(uv[0]);
        node.properties.push(Property {
            name: "to_uv".into(),
            value: Value::Transform(m),
            pos,
            used: Default::default(),
        });
    }
    Ok(())
}
