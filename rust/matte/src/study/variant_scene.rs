//! Derived scenes: a study scene with extra properties, written as a new XML file that both
//! renderers load like any scene.
//!
//! The study scenes can only choose the plugin (`$bsdf`); a model *variant* (Wolff's
//! `normalization`, Oren–Nayar's `model`) is a property inside the `<bsdf>`, and the
//! convergence series renders only a crop of the film. So the scene text is copied with a
//! few byte-range edits located by roxmltree (the rest of the file, comments and layout
//! included, is kept as it was):
//!
//! * every `<bsdf type="$bsdf">` gets the extra property children (an existing child of the
//!   same name has its value replaced instead, since a name given twice is an error);
//! * every `<film>` gets the extra film properties (e.g. `crop_offset_x`);
//! * `<default name="bsdf">` is set to the variant's plugin, so the file renders the variant
//!   on its own (`matte render …/wolff_raw.xml`);
//! * relative file names (`<string name="filename" value=…>`, any `filename=` attribute such
//!   as `<include filename=…>`) are made absolute against the original scene's folder,
//!   because the derived file lives elsewhere. Values starting with `$` are left to the
//!   parameter they name.
//!
//! An asset named with a relative path inside an *included* file resolves against the main
//! scene's folder (`docs/renderer-semantics.md` §1, include pitfall), which is now the output folder; such scenes
//! are refused with an error naming the included file instead of silently losing the asset.

use std::ops::Range;
use std::path::{Path, PathBuf};

/// One property child, e.g. `<string name="normalization" value="raw"/>`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DerivedProperty {
    /// `string`, `integer`, `float` or `boolean`.
    pub tag: &'static str,
    pub name: String,
    pub value: String,
}

impl DerivedProperty {
    pub fn string(name: &str, value: &str) -> DerivedProperty {
        DerivedProperty { tag: "string", name: name.into(), value: value.into() }
    }
    pub fn integer(name: &str, value: i64) -> DerivedProperty {
        DerivedProperty { tag: "integer", name: name.into(), value: value.to_string() }
    }
}

/// What a derived scene changes.
#[derive(Clone, Debug, Default)]
pub struct Derivation {
    /// New value of `<default name="bsdf">` (if the scene has one).
    pub bsdf: Option<String>,
    /// Set in every `<bsdf type="$bsdf">`; at least one must exist when this is not empty.
    pub bsdf_properties: Vec<DerivedProperty>,
    /// Set in every `<film>`; at least one must exist when this is not empty.
    pub film_properties: Vec<DerivedProperty>,
}

struct Editor<'a> {
    text: &'a str,
    doc: &'a roxmltree::Document<'a>,
    source: &'a Path,
    edits: Vec<(Range<usize>, String)>,
}

impl Editor<'_> {
    fn err(&self, pos: usize, msg: impl std::fmt::Display) -> String {
        format!("{}: line {}: {msg}", self.source.display(), self.doc.text_pos_at(pos).row)
    }

    /// Byte index of the `>` ending the start tag of `node` (quotes skipped), and whether the
    /// element is self-closing (`/>`).
    fn start_tag_end(&self, node: roxmltree::Node) -> Result<(usize, bool), String> {
        let start = node.range().start;
        let mut quote = None;
        for (i, c) in self.text[start..].char_indices() {
            match (quote, c) {
                (Some(q), c) if c == q => quote = None,
                (Some(_), _) => {}
                (None, '"' | '\'') => quote = Some(c),
                (None, '>') => {
                    let gt = start + i;
                    return Ok((gt, self.text[..gt].ends_with('/')));
                }
                _ => {}
            }
        }
        Err(self.err(start, "unterminated start tag"))
    }

    /// Leading whitespace of the line `pos` is on (for the inserted children's layout).
    fn indent_at(&self, pos: usize) -> &str {
        let line = self.text[..pos].rfind('\n').map_or(0, |i| i + 1);
        let lead = &self.text[line..pos];
        let n = lead.len() - lead.trim_start().len();
        &lead[..n]
    }

    fn replace_value(&mut self, node: roxmltree::Node, attr: &str, value: &str) -> Result<(), String> {
        let a = node
            .attributes()
            .find(|a| a.name() == attr)
            .ok_or_else(|| self.err(node.range().start, format!("<{}> has no {attr}=", node.tag_name().name())))?;
        self.edits.push((a.range_value(), crate::markup::escape(value)));
        Ok(())
    }

    /// Sets `props` in `node`: replaces the value of an existing child with the same name and
    /// tag, inserts the others after the start tag.
    fn set_properties(&mut self, node: roxmltree::Node, props: &[DerivedProperty]) -> Result<(), String> {
        let mut insert = Vec::new();
        for p in props {
            let existing = node.children().find(|c| c.is_element() && c.attribute("name") == Some(p.name.as_str()));
            match existing {
                Some(c) if c.tag_name().name() == p.tag => self.replace_value(c, "value", &p.value)?,
                Some(c) => {
                    return Err(self.err(
                        c.range().start,
                        format!(
                            "<{}> already has a <{}> named \"{}\"; cannot set it as <{}>",
                            node.tag_name().name(),
                            c.tag_name().name(),
                            p.name,
                            p.tag
                        ),
                    ));
                }
                None => insert.push(p),
            }
        }
        if insert.is_empty() {
            return Ok(());
        }
        let indent = self.indent_at(node.range().start).to_string();
        let mut children = String::new();
        for p in insert {
            children.push_str(&format!(
                "\n{indent}    <{} name=\"{}\" value=\"{}\"/>",
                p.tag,
                crate::markup::escape(&p.name),
                crate::markup::escape(&p.value)
            ));
        }
        let (gt, self_closing) = self.start_tag_end(node)?;
        if self_closing {
            // `<bsdf …/>` becomes `<bsdf …>children</bsdf>`.
            self.edits.push((gt - 1..gt + 1, format!(">{children}\n{indent}</{}>", node.tag_name().name())));
        } else {
            self.edits.push((gt + 1..gt + 1, children));
        }
        Ok(())
    }

    /// Makes a relative file name absolute against `base`; `None` if it stays as it is.
    fn absolute(base: &Path, value: &str) -> Option<String> {
        if value.starts_with('$') || Path::new(value).is_absolute() {
            return None;
        }
        Some(base.join(value).to_string_lossy().into_owned())
    }

    fn apply(mut self) -> Result<String, String> {
        self.edits.sort_by_key(|(r, _)| (r.start, r.end));
        let mut out = String::with_capacity(self.text.len() + 1024);
        let mut at = 0;
        for (r, s) in &self.edits {
            if r.start < at {
                return Err(self.err(r.start, "two edits overlap (an element edited twice)"));
            }
            out.push_str(&self.text[at..r.start]);
            out.push_str(s);
            at = r.end;
        }
        out.push_str(&self.text[at..]);
        Ok(out)
    }
}

/// The folder relative names in `source` resolve against, as an absolute path.
fn base_dir(source: &Path) -> Result<PathBuf, String> {
    let parent = source.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::path::absolute(parent).map_err(|e| format!("{}: {e}", source.display()))
}

/// The derived scene's text. `source` is the original file (for error messages and as the
/// base of relative file names).
pub fn derive_text(text: &str, source: &Path, d: &Derivation) -> Result<String, String> {
    let doc = roxmltree::Document::parse(text).map_err(|e| format!("{}: malformed XML: {e}", source.display()))?;
    let base = base_dir(source)?;
    let mut ed = Editor { text, doc: &doc, source, edits: Vec::new() };
    let (mut bsdfs, mut films) = (0, 0);
    for node in doc.descendants().filter(roxmltree::Node::is_element) {
        let tag = node.tag_name().name();
        if tag == "bsdf" && node.attribute("type") == Some("$bsdf") {
            bsdfs += 1;
            ed.set_properties(node, &d.bsdf_properties)?;
        }
        if tag == "film" {
            films += 1;
            ed.set_properties(node, &d.film_properties)?;
        }
        if tag == "default"
            && node.attribute("name") == Some("bsdf")
            && let Some(b) = &d.bsdf
        {
            ed.replace_value(node, "value", b)?;
        }
        if let Some(v) = node.attribute("filename") {
            let abs = Editor::absolute(&base, v);
            if tag == "include" && !v.starts_with('$') {
                check_include(Path::new(abs.as_deref().unwrap_or(v)), 0)?;
            }
            if let Some(abs) = abs {
                ed.replace_value(node, "filename", &abs)?;
            }
        }
        if tag == "string"
            && node.attribute("name") == Some("filename")
            && let Some(v) = node.attribute("value")
            && let Some(abs) = Editor::absolute(&base, v)
        {
            ed.replace_value(node, "value", &abs)?;
        }
    }
    let root = doc.root_element().range().start;
    if bsdfs == 0 && !d.bsdf_properties.is_empty() {
        return Err(ed.err(root, "no <bsdf type=\"$bsdf\"> to set the variant's properties in"));
    }
    if films == 0 && !d.film_properties.is_empty() {
        return Err(ed.err(root, "no <film> to set the film properties in"));
    }
    // Provenance, just before the root element (a comment may not contain "--").
    let what: Vec<String> =
        d.bsdf_properties.iter().chain(&d.film_properties).map(|p| format!("{}={}", p.name, p.value)).collect();
    let note =
        format!("Derived by `matte study` from {} ({}); edit the original instead.", source.display(), what.join(", "))
            .replace("--", "- -");
    ed.edits.push((root..root, format!("<!-- {note} -->\n")));
    ed.apply()
}

/// Refuses an included file (and its includes) that names an asset with a relative path.
fn check_include(path: &Path, depth: u32) -> Result<(), String> {
    if depth > 16 {
        return Err(format!("{}: includes nested more than 16 deep", path.display()));
    }
    let Ok(text) = std::fs::read_to_string(path) else { return Ok(()) }; // the loader reports a missing file
    let doc = roxmltree::Document::parse(&text).map_err(|e| format!("{}: malformed XML: {e}", path.display()))?;
    let base = base_dir(path)?;
    for node in doc.descendants().filter(roxmltree::Node::is_element) {
        if node.tag_name().name() == "include"
            && let Some(v) = node.attribute("filename")
        {
            check_include(&if Path::new(v).is_absolute() { PathBuf::from(v) } else { base.join(v) }, depth + 1)?;
        } else if node.tag_name().name() == "string"
            && node.attribute("name") == Some("filename")
            && let Some(v) = node.attribute("value")
            && Editor::absolute(&base, v).is_some()
        {
            return Err(format!(
                "{}: line {}: relative asset \"{v}\" in an included file would resolve against the derived scene's folder; make it absolute to derive a variant",
                path.display(),
                doc.text_pos_at(node.range().start).row
            ));
        }
    }
    Ok(())
}

/// Reads `source`, derives it and writes the result to `dest` (creating its folder).
pub fn write_derived(source: &Path, dest: &Path, d: &Derivation) -> Result<(), String> {
    let text = std::fs::read_to_string(source).map_err(|e| format!("{}: {e}", source.display()))?;
    let derived = derive_text(&text, source, d)?;
    if let Some(dir) = dest.parent() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    std::fs::write(dest, derived).map_err(|e| format!("{}: {e}", dest.display()))
}
