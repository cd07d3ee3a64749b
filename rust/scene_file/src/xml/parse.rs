//! The XML walk: elements → [`RawScene`] nodes, with `$` substitution on every attribute,
//! `<default>`, `<include>`, `<alias>` and all property tags (`src/core/parser.cpp::
//! parse_xml_node`, `parse_file_impl`; docs/renderer-semantics.md §1).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use roxmltree::{Document, Node, ParsingOptions};

use super::attrs::Attrs;
use super::properties::{Property, Value};
use super::property_values::{is_value_tag, property_value, spectrum_file};
use super::raw::{RawChild, RawNode, RawScene, Target};
use super::substitute::Substitutions;
use super::transform::build_transform;
use crate::error::{SceneError, SourcePos};

/// Includes nest at most this deep (Mitsuba's `ParserConfig::max_include_depth`).
pub(crate) const MAX_INCLUDE_DEPTH: usize = 15;

/// Object element names (Mitsuba's `interpret_tag`, `TagType::Object`), `<scene>` aside.
fn is_object_tag(tag: &str) -> bool {
    matches!(
        tag,
        "bsdf"
            | "shape"
            | "emitter"
            | "sensor"
            | "film"
            | "rfilter"
            | "sampler"
            | "integrator"
            | "texture"
            | "medium"
            | "phase"
            | "volume"
    )
}

/// One XML file being walked.
struct FileCtx<'a, 'input> {
    doc: &'a Document<'input>,
    path: Arc<PathBuf>,
    version: [u32; 3],
    depth: usize,
}

impl FileCtx<'_, '_> {
    fn pos(&self, node: Node) -> SourcePos {
        let p = self.doc.text_pos_at(node.range().start);
        SourcePos::new(self.path.clone(), p.row, p.col)
    }
}

/// The walk's state: nodes so far and the parameters, shared with every include.
pub(crate) struct Parser {
    pub scene: RawScene,
    pub params: Substitutions,
    /// The folders Mitsuba's `FileResolver` holds while this file is parsed, first searched
    /// first: the main scene's folder and the working directory at the start (`load_file`
    /// prepends the scene's folder), `<path>` folders prepended as they come, and while an
    /// `<include>`d file is parsed, a copy with the including file's folder in front (thrown
    /// away afterwards, with any `<path>` the included file added).
    resolver: Vec<PathBuf>,
}

/// Mitsuba's `FileResolver::resolve`: the first folder in `resolver` where `name` exists,
/// else `name` unchanged (so relative to the working directory).
fn resolve_in(resolver: &[PathBuf], name: &Path) -> PathBuf {
    if name.is_absolute() {
        return name.to_path_buf();
    }
    resolver.iter().map(|d| d.join(name)).find(|p| p.exists()).unwrap_or_else(|| name.to_path_buf())
}

/// Parses `text` (malformed XML → error at the position roxmltree reports).
fn parse_xml<'input>(text: &'input str, path: &Arc<PathBuf>) -> Result<Document<'input>, SceneError> {
    let opt = ParsingOptions { allow_dtd: true, ..ParsingOptions::default() };
    Document::parse_with_options(text, opt).map_err(|e| {
        let p = e.pos();
        let msg = e.to_string().replace(&format!(" at {p}"), "");
        SceneError::at(&SourcePos::new(path.clone(), p.row, p.col), format!("malformed XML: {msg}"))
    })
}

/// `"major.minor.patch"` (Mitsuba's `util::Version`: three parts split at spaces or dots).
fn parse_version(s: &str, pos: &SourcePos) -> Result<[u32; 3], SceneError> {
    let parts: Vec<&str> = s.split([' ', '.']).filter(|p| !p.is_empty()).collect();
    let bad =
        || SceneError::at(pos, format!("invalid version number \"{s}\" (expected major.minor.patch, e.g. \"3.0.0\")"));
    if parts.len() != 3 {
        return Err(bad());
    }
    let mut v = [0u32; 3];
    for (p, out) in parts.iter().zip(v.iter_mut()) {
        *out = p.parse().map_err(|_| bad())?;
    }
    Ok(v)
}

impl Parser {
    pub(crate) fn new(overrides: &[(String, String)]) -> Self {
        Parser { scene: RawScene::default(), params: Substitutions::new(overrides), resolver: Vec::new() }
    }

    /// The attributes of `el` after `$` substitution, in document order.
    fn attrs(&mut self, ctx: &FileCtx, el: Node) -> Result<Attrs, SceneError> {
        let pos = ctx.pos(el);
        let mut list = Vec::new();
        for a in el.attributes() {
            let name = match a.namespace() {
                Some(_) => format!("{{{}}}{}", a.namespace().unwrap_or(""), a.name()),
                None => a.name().to_string(),
            };
            list.push((name, self.params.substitute(a.value(), &pos)?));
        }
        Ok(Attrs::new(el.tag_name().name(), pos, list))
    }

    /// The main file: its root must be `<scene version="...">`; it becomes node 0.
    pub(crate) fn parse_main(&mut self, text: &str, path: &Path) -> Result<(), SceneError> {
        let path = Arc::new(path.to_path_buf());
        self.resolver = vec![path.parent().unwrap_or(Path::new("")).to_path_buf()];
        self.resolver.extend(std::env::current_dir().ok());
        let doc = parse_xml(text, &path)?;
        let root = doc.root_element();
        let mut ctx = FileCtx { doc: &doc, path, version: [3, 0, 0], depth: 0 };
        let a = self.attrs(&ctx, root)?;
        if root.tag_name().name() != "scene" || root.tag_name().namespace().is_some() {
            return Err(a.err(format!("the root element must be <scene version=\"...\">, found <{}>", a.tag)));
        }
        ctx.version = self.root_version(&a)?;
        a.check(&["!version"])?;
        self.scene.nodes.push(RawNode {
            tag: "scene".into(),
            plugin: String::new(),
            id: None,
            pos: a.pos.clone(),
            version: ctx.version,
            properties: Default::default(),
            children: Vec::new(),
        });
        self.children(&ctx, root, 0, false)
    }

    fn root_version(&self, a: &Attrs) -> Result<[u32; 3], SceneError> {
        let v =
            a.get("version").ok_or_else(|| a.err(format!("missing version attribute in root element <{}>", a.tag)))?;
        parse_version(v, &a.pos)
    }

    /// Walks the element children of `el` into node `parent`. `included_root`: `el` is the
    /// `<scene>` root of an included file, whose children are spliced into `parent`.
    fn children(&mut self, ctx: &FileCtx, el: Node, parent: usize, included_root: bool) -> Result<(), SceneError> {
        for child in el.children().filter(Node::is_element) {
            self.element(ctx, child, parent, included_root)?;
        }
        Ok(())
    }

    fn element(&mut self, ctx: &FileCtx, el: Node, parent: usize, included_root: bool) -> Result<(), SceneError> {
        let mut a = self.attrs(ctx, el)?;
        let tag = a.tag.clone();
        if el.tag_name().namespace().is_some() {
            return Err(a.err(format!("unsupported XML element <{tag}> (namespaced)")));
        }
        let is_value = is_value_tag(&tag) && !(tag == "spectrum" && a.get("type").is_some());
        if is_value || tag == "transform" || tag == "ref" {
            if included_root {
                return Err(a.err(format!(
                    "<{tag}> directly inside an included <scene> is ignored by Mitsuba 3; move it into the including file"
                )));
            }
            if tag != "transform"
                && let Some(c) = el.children().find(Node::is_element)
            {
                return Err(a.err(format!("<{}> cannot occur inside <{tag}>", c.tag_name().name())));
            }
        }
        match tag.as_str() {
            _ if is_object_tag(&tag) || (tag == "spectrum" && a.get("type").is_some()) => {
                self.object(ctx, el, a, parent)
            }
            "transform" => {
                a.check(&["!name"])?;
                let mut ops = Vec::new();
                for op in el.children().filter(Node::is_element) {
                    if let Some(c) = op.children().find(Node::is_element) {
                        return Err(SceneError::at(
                            &ctx.pos(c),
                            format!("<{}> cannot occur inside <{}>", c.tag_name().name(), op.tag_name().name()),
                        ));
                    }
                    ops.push(self.attrs(ctx, op)?);
                }
                let m = build_transform(ops)?;
                self.property(parent, &a, Value::Transform(m))
            }
            // A spectrum file is resolved at parse time, with the resolver of the moment.
            "spectrum" if a.get("filename").is_some_and(|f| !f.is_empty()) && a.get("value").is_none() => {
                let path = resolve_in(&self.resolver, Path::new(a.get("filename").unwrap_or_default()));
                let v = spectrum_file(&a, &path)?;
                self.property(parent, &a, v)
            }
            _ if is_value => {
                let v = property_value(&mut a)?;
                self.property(parent, &a, v)
            }
            "ref" => {
                a.check(&["!id", "name"])?;
                let child = RawChild {
                    name: a.get("name").map(str::to_string),
                    target: Target::Ref(a.required("id")?.to_string()),
                    pos: a.pos.clone(),
                };
                self.scene.add_child(parent, child)
            }
            "default" => {
                a.check(&["!name", "!value"])?;
                let name = a.required("name")?;
                if name.is_empty() {
                    return Err(a.err("<default>: name must be non-empty"));
                }
                self.params.add_default(name, a.required("value")?);
                Ok(())
            }
            "alias" => {
                a.check(&["!id", "!as"])?;
                let (src, dst) = (a.required("id")?, a.required("as")?);
                if self.scene.ids.contains_key(dst) {
                    return Err(a.err(format!("alias destination id \"{dst}\" already exists")));
                }
                let Some(&(index, _)) = self.scene.ids.get(src) else {
                    return Err(
                        a.err(format!("alias source id \"{src}\" not found (it must be defined before the alias)"))
                    );
                };
                self.scene.add_id(dst, index, &a.pos)
            }
            "include" => self.include(ctx, a, parent),
            "scene" => Err(a.err("<scene> can only be the root element")),
            "translate" | "rotate" | "scale" | "matrix" | "lookat" => {
                Err(a.err(format!("transform operation <{tag}> can only appear inside a <transform>")))
            }
            "path" => self.search_path(ctx, &a, parent),
            _ => Err(a.err(format!("unknown element <{tag}>"))),
        }
    }

    /// `<path value="..."/>` (Mitsuba `src/core/parser.cpp`, `TagType::Resource`): only
    /// directly under the root of its file; a relative folder is tried against the folder of
    /// the XML file it appears in, then through the file resolver; it must exist. It is put
    /// in front of the resolver (`FileResolver::prepend`). In the main file it also stays for
    /// the scene's asset files; in an included file it lasts until the end of that file
    /// (Mitsuba parses an include with a copy of the resolver and restores the original).
    fn search_path(&mut self, ctx: &FileCtx, a: &Attrs, parent: usize) -> Result<(), SceneError> {
        a.check(&["!value"])?;
        if parent != 0 {
            return Err(a.err("<path> can only be a child of the root <scene>"));
        }
        let value = a.required("value")?;
        let mut folder = PathBuf::from(value);
        if !folder.is_absolute() {
            folder = ctx.path.parent().unwrap_or(Path::new("")).join(value);
            if !folder.exists() {
                folder = resolve_in(&self.resolver, Path::new(value));
            }
        }
        if !folder.is_dir() {
            return Err(a.err(format!("<path>: folder \"{}\" not found", folder.display())));
        }
        if ctx.depth == 0 {
            self.scene.search_paths.insert(0, folder.clone());
        }
        self.resolver.insert(0, folder);
        Ok(())
    }

    fn property(&mut self, parent: usize, a: &Attrs, value: Value) -> Result<(), SceneError> {
        let p = Property { name: a.required("name")?.to_string(), value, pos: a.pos.clone(), used: Default::default() };
        self.scene.add_property(parent, p)
    }

    /// An object element (also `<spectrum type=...>`, a texture): a new node, registered as
    /// a child of `parent` and under its id before its own children are walked.
    fn object(&mut self, ctx: &FileCtx, el: Node, a: Attrs, parent: usize) -> Result<(), SceneError> {
        a.check(&["!type", "id", "name"])?;
        let index = self.new_object(ctx, &a)?;
        let child =
            RawChild { name: a.get("name").map(str::to_string), target: Target::Node(index), pos: a.pos.clone() };
        self.scene.add_child(parent, child)?;
        self.children(ctx, el, index, false)
    }

    fn new_object(&mut self, ctx: &FileCtx, a: &Attrs) -> Result<usize, SceneError> {
        let index = self.scene.nodes.len();
        let id = a.get("id").filter(|s| !s.is_empty()).map(str::to_string);
        if let Some(id) = &id {
            self.scene.add_id(id, index, &a.pos)?;
        }
        let tag = if a.tag == "spectrum" { "texture".to_string() } else { a.tag.clone() };
        self.scene.nodes.push(RawNode {
            tag,
            plugin: a.required("type")?.to_string(),
            id,
            pos: a.pos.clone(),
            version: ctx.version,
            properties: Default::default(),
            children: Vec::new(),
        });
        Ok(index)
    }

    /// `<include filename name>`: the file is resolved with the including file's folder in
    /// front of the resolver, then the resolver's folders (Mitsuba's `TagType::Include`); it
    /// is parsed with that resolver, restored afterwards. A `<scene>` root has its children
    /// spliced into `parent`; any other object root becomes one child of `parent` (named by
    /// the include's `name`). Parameters are shared both ways.
    fn include(&mut self, ctx: &FileCtx, a: Attrs, parent: usize) -> Result<(), SceneError> {
        a.check(&["!filename", "name"])?;
        if ctx.depth + 1 >= MAX_INCLUDE_DEPTH {
            return Err(a.err(format!("exceeded the maximum include depth of {MAX_INCLUDE_DEPTH}")));
        }
        let filename = a.required("filename")?;
        let saved = self.resolver.clone();
        self.resolver.insert(0, ctx.path.parent().unwrap_or(Path::new("")).to_path_buf());
        let path = resolve_in(&self.resolver, Path::new(filename));
        let result = std::fs::read_to_string(&path)
            .map_err(|e| a.err(format!("cannot read included file \"{}\": {e}", path.display())))
            .and_then(|text| {
                self.include_text(&text, Arc::new(path), ctx.depth + 1, &a, parent).map_err(|e| SceneError {
                    message: format!("{} (in a file included at {})", e.message, a.pos),
                    ..e
                })
            });
        self.resolver = saved;
        result
    }

    fn include_text(
        &mut self,
        text: &str,
        path: Arc<PathBuf>,
        depth: usize,
        inc: &Attrs,
        parent: usize,
    ) -> Result<(), SceneError> {
        let doc = parse_xml(text, &path)?;
        let root = doc.root_element();
        let mut ctx = FileCtx { doc: &doc, path, version: [3, 0, 0], depth };
        let a = self.attrs(&ctx, root)?;
        ctx.version = self.root_version(&a)?;
        if a.tag == "scene" {
            a.check(&["!version"])?;
            return self.children(&ctx, root, parent, true);
        }
        if !is_object_tag(&a.tag) {
            return Err(a.err(format!("the root of an included file must be <scene> or an object, found <{}>", a.tag)));
        }
        a.check(&["!version", "!type", "id", "name"])?;
        let index = self.new_object(&ctx, &a)?;
        let name = inc.get("name").or(a.get("name")).map(str::to_string);
        self.scene.add_child(parent, RawChild { name, target: Target::Node(index), pos: inc.pos.clone() })?;
        self.children(&ctx, root, index, false)
    }
}
