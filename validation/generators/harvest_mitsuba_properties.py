#!/usr/bin/env python3
"""Harvests, from Mitsuba 3's C++ sources, the properties each plugin reads, and writes them
as Rust data: `rust/render/src/load/mitsuba_plugins.rs`.

    python3 validation/generators/harvest_mitsuba_properties.py MITSUBA_ROOT [-o rust/render/src/load/mitsuba_plugins.rs]

MITSUBA_ROOT is a checkout (or `git archive`) of mitsuba-renderer/mitsuba3 at tag v3.9.1 with
`src/` and `include/`. Run by hand when Mitsuba's version changes; tests never run it.

What counts as "read" is what makes Mitsuba's `Properties` mark a property as queried, so that
the plugin accepts it instead of failing with "unreferenced property":

* `props.get<T>("name"[, default])`, `props.get("name", default)`,
  `props.get_texture / get_unbounded_texture / get_emissive_texture / get_volume`,
  `props.get_any`, `props.try_get`, `props.mark_queried("name")`;
* the same reads in the plugin's base-class constructors (the chain from the plugin class's
  declaration, e.g. `PerspectiveCamera : ProjectiveCamera : Sensor : Endpoint`), in local
  headers the plugin includes, and in the helpers that take the `Properties` (`parse_fov`,
  `MicrofacetDistribution(props)`, `lookup_ior(props, "name", default)`).

`props.has_property` alone does not mark a property (only a guard), so it is not a read.
Plugins that iterate over all their properties (`for (auto &p : props)`, `props.keys()`,
`props.unqueried()`) are marked `reads_any_property`. The plugin list is each directory's
`CMakeLists.txt` (`add_plugin(name file.cpp)`); the root `<scene>` is `src/render/scene.cpp`
with its CPU acceleration structures (`scene_embree.inl`, `scene_native.inl`).

Each property records its kind (from `T` or the getter), its default as written in the source,
the default as a plain literal where it is one, and `path:line` of the read. A read guarded by
a condition (e.g. `fov_axis` only with `fov`) is still listed: it is a property Mitsuba can
accept.

The script also prints, per plugin, the names of the docstring's `.. pluginparameters::` table
that were not harvested (and the other way round), for review.
"""

import argparse
import os
import re
import sys

# Plugin directory -> XML tag.
TAG_DIRS = [
    ("bsdfs", "bsdf"),
    ("emitters", "emitter"),
    ("films", "film"),
    ("integrators", "integrator"),
    ("rfilters", "rfilter"),
    ("samplers", "sampler"),
    ("sensors", "sensor"),
    ("shapes", "shape"),
    ("textures", "texture"),
    ("volumes", "volume"),
    ("spectra", "texture"),  # <spectrum type=...> and <texture type=...> are both Texture objects
]

# Where base-class constructors live.
BASE_DIRS = ["src/render", "include/mitsuba/render"]

# Template argument of props.get<T> -> Kind.
TYPE_KINDS = {
    "ScalarFloat": "Float",
    "float": "Float",
    "double": "Float",
    "Float": "Float",
    "bool": "Boolean",
    "int": "Integer",
    "uint32_t": "Integer",
    "ScalarInt32": "Integer",
    "ScalarUInt32": "Integer",
    "int64_t": "Integer",
    "size_t": "Integer",
    "uint64_t": "Integer",
    "std::string": "String",
    "std::string_view": "String",
    "ScalarPoint3f": "Point",
    "ScalarVector3f": "Vector",
    "ScalarColor3f": "Color",
    "ScalarAffineTransform4f": "Transform",
    "ScalarAffineTransform3f": "Transform",
    "ScalarTransform4f": "Transform",
}
GETTER_KINDS = {
    "get_texture": "Texture",
    "get_unbounded_texture": "UnboundedTexture",
    "get_emissive_texture": "EmissiveTexture",
    "get_volume": "Volume",
    "get_any": "Object",
    "try_get": "Any",
    "mark_queried": "Any",
}
READ_RE = re.compile(
    r"\bprops\s*\.\s*(get|get_texture|get_unbounded_texture|get_emissive_texture|get_volume|get_any|"
    r"try_get|mark_queried)\b"
)
ANY_RE = re.compile(
    r"for\s*\(\s*(?:const\s+)?auto\s*&+\s*\w+\s*:\s*props\s*\)|\bprops\s*\.\s*(?:keys|items|unqueried)\s*\("
)


def strip_comments(text):
    """C/C++ comments blanked to spaces (newlines kept, so line numbers stay right)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append(text[i : j + 1])
            i = j + 1
        elif c == "'" and i + 2 < n:
            j = i + 1
            while j < n and text[j] != "'":
                j += 2 if text[j] == "\\" else 1
            out.append(text[i : j + 1])
            i = j + 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def matching(text, i, open_c, close_c):
    """Index just past the bracket closing the one at text[i]."""
    depth = 0
    j = i
    while j < len(text):
        c = text[j]
        if c == '"':
            j += 1
            while text[j] != '"':
                j += 2 if text[j] == "\\" else 1
        elif c == open_c:
            depth += 1
        elif c == close_c:
            depth -= 1
            if depth == 0:
                return j + 1
        j += 1
    raise ValueError("unbalanced bracket")


def split_args(s):
    """Top-level comma split of a call's argument text."""
    args, depth, cur, i = [], 0, [], 0
    while i < len(s):
        c = s[i]
        if c == '"':
            j = i + 1
            while s[j] != '"':
                j += 2 if s[j] == "\\" else 1
            cur.append(s[i : j + 1])
            i = j + 1
            continue
        if c in "([{<":
            depth += 1
        elif c in ")]}>":
            depth -= 1
        if c == "," and depth == 0:
            args.append("".join(cur).strip())
            cur = []
        else:
            cur.append(c)
        i += 1
    if "".join(cur).strip():
        args.append("".join(cur).strip())
    return args


def literal(default):
    """A C++ default as a plain literal ("0.01", "true", "x"), or None if it is an expression."""
    if default is None:
        return None
    d = default.strip()
    m = re.fullmatch(r'"((?:[^"\\]|\\.)*)"', d)
    if m:
        return m.group(1)
    if d in ("true", "false"):
        return d
    m = re.fullmatch(r"([+-]?)(\d+\.?\d*|\.\d+)(?:[eE]([+-]?\d+))?[fF]?", d)
    if m:
        return "%.9g" % float(d.rstrip("fF"))
    m = re.fullmatch(r"([+-]?\d+)[uUlL]*", d)
    if m:
        return m.group(1)
    return None


class Read:
    def __init__(self, name, kind, default, source):
        self.name, self.kind, self.default, self.source = name, kind, default, source


def line_of(text, i):
    return text.count("\n", 0, i) + 1


def reads_in(text, rel, lo=0, hi=None):
    """The property reads in text[lo:hi] (comment-free text of file `rel`)."""
    hi = len(text) if hi is None else hi
    out = []
    for m in READ_RE.finditer(text, lo, hi):
        getter = m.group(1)
        j = m.end()
        while text[j].isspace():
            j += 1
        targ = None
        if text[j] == "<":
            k = matching(text, j, "<", ">")
            targ = re.sub(r"\s+", "", text[j + 1 : k - 1])
            j = k
            while text[j].isspace():
                j += 1
        if text[j] != "(":
            continue
        k = matching(text, j, "(", ")")
        args = split_args(text[j + 1 : k - 1])
        if not args or not re.fullmatch(r'"[^"]*"', args[0]):
            continue  # a computed name: not a fixed property
        name = args[0][1:-1]
        default = args[1] if len(args) > 1 and getter != "mark_queried" else None
        if getter == "get":
            if targ is None:
                lit = literal(default)
                kind = "Float" if lit is not None and re.fullmatch(r"[-+\d.e]+", lit) else "Any"
            elif targ in TYPE_KINDS:
                kind = TYPE_KINDS[targ]
            else:
                kind = "Object"
        else:
            kind = GETTER_KINDS[getter]
        out.append(Read(name, kind, default, f"{rel}:{line_of(text, m.start())}"))
    # lookup_ior(props, "int_ior", "bk7"): a float or the name of a material.
    for m in re.finditer(r'\blookup_ior\s*\(\s*props\s*,\s*"(\w+)"\s*,\s*([^)]*)\)', text[lo:hi]):
        out.append(Read(m.group(1), "Any", m.group(2).strip(), f"{rel}:{line_of(text, lo + m.start())}"))
    return out


class Source:
    """A source file, comment-free, with its path relative to MITSUBA_ROOT."""

    cache = {}

    def __init__(self, root, rel):
        self.rel = rel
        with open(os.path.join(root, rel), encoding="utf-8") as f:
            self.raw = f.read()
        self.text = strip_comments(self.raw)

    @classmethod
    def get(cls, root, rel):
        if rel not in cls.cache:
            cls.cache[rel] = Source(root, rel)
        return cls.cache[rel]


def function_bodies(src, pattern):
    """(start, end) of each body of the functions/constructors whose signature matches
    `pattern` (initialiser lists included)."""
    spans = []
    for m in re.finditer(pattern, src.text):
        p = src.text.index("(", m.start())
        k = matching(src.text, p, "(", ")")
        b = k
        while b < len(src.text) and src.text[b] not in "{;":
            if src.text[b] == "(":
                b = matching(src.text, b, "(", ")")
                continue
            b += 1
        if b >= len(src.text) or src.text[b] == ";":
            continue  # a declaration
        # Initialiser lists can hold braces ({ ... }) before the body; take the last brace
        # group that starts the body: the first `{` preceded by `)` or the signature.
        e = matching(src.text, b, "{", "}")
        spans.append((m.start(), e))
    return spans


class Mitsuba:
    def __init__(self, root):
        self.root = root
        self.base_files = []
        for d in BASE_DIRS:
            for f in sorted(os.listdir(os.path.join(root, d))):
                if f.endswith((".cpp", ".h", ".inl")):
                    self.base_files.append(f"{d}/{f}")
        # Class -> parent class, from `class MI_EXPORT_LIB Name : public Parent<...>`.
        self.parent = {}
        for rel in self.base_files + ["include/mitsuba/render/mesh.h"]:
            src = Source.get(root, rel)
            for m in re.finditer(r"\bclass\s+(?:MI_EXPORT_LIB\s+)?(\w+)\s*(?:final\s*)?:\s*public\s+(\w+)", src.text):
                self.parent.setdefault(m.group(1), m.group(2))

    def ctor_reads(self, cls):
        """Reads in every constructor of base class `cls` that takes the Properties."""
        out = []
        pat_out = rf"\b{cls}\s*<[^>]*>\s*::\s*{cls}\s*\(\s*const\s+Properties\s*&"
        pat_in = rf"(?<![:~\w]){cls}\s*\(\s*const\s+Properties\s*&\s*props"
        for rel in self.base_files:
            src = Source.get(self.root, rel)
            for pat in (pat_out, pat_in):
                for lo, hi in function_bodies(src, pat):
                    out += reads_in(src.text, rel, lo, hi)
        return out

    def chain(self, cls):
        out = []
        c = self.parent.get(cls)
        while c and c not in ("Object", "JitObject"):
            out.append(c)
            c = self.parent.get(c)
        return out

    def helpers(self, text):
        """Reads of the Properties helpers `text` calls."""
        out = []
        if re.search(r"\bparse_fov\s*\(\s*props\b", text):
            src = Source.get(self.root, "src/render/sensor.cpp")
            for lo, hi in function_bodies(src, r"\bdouble\s+parse_fov\s*\(\s*const\s+Properties"):
                out += reads_in(src.text, src.rel, lo, hi)
        # `MicrofacetDistribution<ScalarFloat, Spectrum> distr(props);` (or a temporary).
        if re.search(r"\bMicrofacetDistribution\s*(?:<[^;{}()]*>)?\s*(?:\w+\s*)?\(\s*props\s*[,)]", text):
            src = Source.get(self.root, "include/mitsuba/render/microfacet.h")
            for lo, hi in function_bodies(src, r"(?<![:~\w])MicrofacetDistribution\s*\(\s*const\s+Properties"):
                out += reads_in(src.text, src.rel, lo, hi)
        return out


def local_includes(root, rel, seen=None):
    seen = set() if seen is None else seen
    src = Source.get(root, rel)
    d = os.path.dirname(rel)
    for m in re.finditer(r'#\s*include\s+"([^"]+)"', src.text):
        inc = os.path.normpath(os.path.join(d, m.group(1)))
        if inc not in seen and os.path.exists(os.path.join(root, inc)):
            seen.add(inc)
            local_includes(root, inc, seen)
    return seen


def plugin_list(root):
    out = []
    for d, tag in TAG_DIRS:
        cm = os.path.join(root, "src", d, "CMakeLists.txt")
        with open(cm) as f:
            for m in re.finditer(r"add_plugin\(\s*(\w+)\s+(\w+\.cpp)", f.read()):
                out.append((tag, m.group(1), f"src/{d}/{m.group(2)}"))
    return out


def doc_parameters(raw):
    """Names of the `.. pluginparameters::` table(s) in a plugin's docstring."""
    names = []
    for block in re.finditer(r"\.\. pluginparameters::(.*?)(?:\n\s*\*?\s*\n\s*\*?\s*(?:\.\. |[A-Z])|\*/)", raw, re.S):
        for m in re.finditer(r"\*\s+-\s+([a-z_][\w]*(?:\s*,\s*[a-z_]\w*)*)\s*\n", block.group(1)):
            for n in m.group(1).split(","):
                names.append(n.strip())
    return names


def merge(reads):
    """One entry per name: the first read gives source and default, the kinds are joined."""
    by = {}
    for r in reads:
        if r.name not in by:
            by[r.name] = r
        else:
            old = by[r.name]
            if old.kind != r.kind:
                # A texture read subsumes a float read of the same name, else accept anything.
                kinds = {old.kind, r.kind}
                if kinds <= {"Texture", "UnboundedTexture", "EmissiveTexture", "Float"}:
                    old.kind = (
                        "UnboundedTexture"
                        if "UnboundedTexture" in kinds
                        else ("EmissiveTexture" if "EmissiveTexture" in kinds else "Texture")
                    )
                elif "Any" in kinds:
                    old.kind = "Any"
                elif kinds == {"Point", "Vector"}:
                    old.kind = "Point"
                else:
                    old.kind = "Any"
            if old.default is None and r.default is not None:
                old.default = r.default
    return sorted(by.values(), key=lambda r: r.name)


def harvest(root):
    m = Mitsuba(root)
    plugins = []
    # The root <scene>.
    reads = []
    for rel in ["src/render/scene.cpp", "src/render/scene_embree.inl", "src/render/scene_native.inl"]:
        src = Source.get(root, rel)
        reads += reads_in(src.text, rel)
    plugins.append(("scene", "scene", "src/render/scene.cpp", merge(reads), False, []))
    for tag, name, rel in plugin_list(root):
        src = Source.get(root, rel)
        files = [rel] + sorted(local_includes(root, rel))
        reads, any_prop = [], False
        for f in files:
            s = Source.get(root, f)
            reads += reads_in(s.text, f)
            reads += m.helpers(s.text)
            any_prop = any_prop or bool(ANY_RE.search(s.text))
        exported = re.search(r"MI_EXPORT_PLUGIN\(\s*(\w+)\s*\)", src.text)
        cls = exported.group(1) if exported else None
        bases = []
        if cls:
            d = re.search(rf"\bclass\s+{cls}\s*(?:final\s*)?:\s*public\s+(\w+)", src.text)
            if d:
                bases = [d.group(1)] + m.chain(d.group(1))
        for b in bases:
            reads += m.ctor_reads(b)
        plugins.append((tag, name, rel, merge(reads), any_prop, doc_parameters(src.raw)))
    return plugins


def rust_str(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def opt(s):
    return "None" if s is None else f"Some({rust_str(s)})"


HEADER = """//! Generated by `validation/generators/harvest_mitsuba_properties.py`; do not edit (rerun it).
//! The properties each Mitsuba 3.9.1 plugin reads, harvested from its sources (the
//! plugin's `.cpp`, its base-class constructors and the `Properties` helpers it calls).
//! `rust/render/src/load/no_effect.rs` and the builders in `rust/render/src/load/` decide what matte
//! does with each; `tests/render/load/walk.rs` walks the whole list.

/// How a plugin reads a property (which XML values it takes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Float,
    Integer,
    Boolean,
    String,
    Transform,
    Point,
    Vector,
    Color,
    /// `get_texture`: a float, a colour, a spectrum or a `<texture>`.
    Texture,
    /// `get_emissive_texture`: as `Texture`, read as emission.
    EmissiveTexture,
    /// `get_unbounded_texture`: as `Texture`, values not clamped to [0, 1].
    UnboundedTexture,
    /// `get_volume`: a float, a colour or a `<volume>`.
    Volume,
    /// An object no XML property gives (a Python `Bitmap`, a tensor, a nested reference).
    Object,
    /// Any value (`mark_queried`, `try_get`, or a float-or-string such as `lookup_ior`'s).
    Any,
}

/// One property a plugin reads.
#[derive(Clone, Copy, Debug)]
pub struct PluginProperty {
    pub name: &'static str,
    pub kind: Kind,
    /// The default as written in Mitsuba's source (`None`: the property is required or has
    /// no default in the read).
    pub default: Option<&'static str>,
    /// `default` when it is a plain literal (`"0.01"`, `"true"`, `"x"`).
    pub literal: Option<&'static str>,
    /// `path:line` of the read in Mitsuba 3.9.1.
    pub source: &'static str,
}

/// One plugin: the XML tag (`bsdf`, `shape`, ...), its `type` and what it reads.
#[derive(Clone, Copy, Debug)]
pub struct Plugin {
    pub tag: &'static str,
    pub name: &'static str,
    pub source: &'static str,
    pub properties: &'static [PluginProperty],
    /// The plugin iterates over all its properties (any name may be read).
    pub reads_any_property: bool,
}

/// The plugin (`tag`, `name`), if Mitsuba 3.9.1 has it.
pub fn plugin(tag: &str, name: &str) -> Option<&'static Plugin> {
    PLUGINS.iter().find(|p| p.tag == tag && p.name == name)
}

/// Property `name` of plugin (`tag`, `plugin`).
pub fn property(tag: &str, plugin_name: &str, name: &str) -> Option<&'static PluginProperty> {
    plugin(tag, plugin_name)?.properties.iter().find(|p| p.name == name)
}

"""


def write_rust(plugins, out):
    lines = [HEADER, "pub static PLUGINS: &[Plugin] = &["]
    for tag, name, rel, props, any_prop, _ in plugins:
        lines.append("    Plugin {")
        lines.append(f"        tag: {rust_str(tag)},")
        lines.append(f"        name: {rust_str(name)},")
        lines.append(f"        source: {rust_str(rel)},")
        lines.append(f"        reads_any_property: {'true' if any_prop else 'false'},")
        lines.append("        properties: &[")
        for p in props:
            lines.append(
                f"            PluginProperty {{ name: {rust_str(p.name)}, kind: Kind::{p.kind}, default: {opt(p.default)}, "
                f"literal: {opt(literal(p.default))}, source: {rust_str(p.source)} }},"
            )
        lines.append("        ],")
        lines.append("    },")
    lines.append("];")
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("root", help="Mitsuba 3.9.1 source tree (with src/ and include/)")
    ap.add_argument("-o", "--output", default="rust/render/src/load/mitsuba_plugins.rs")
    a = ap.parse_args()
    plugins = harvest(a.root)
    write_rust(plugins, a.output)
    n = sum(len(p[3]) for p in plugins)
    print(f"{len(plugins)} plugins, {n} properties -> {a.output}")
    for tag, name, _rel, props, _any_prop, docs in plugins:
        got = {p.name for p in props}
        undocumented = sorted(got - set(docs)) if docs else []
        unharvested = sorted(set(docs) - got)
        if unharvested or undocumented:
            print(
                f"  {tag}/{name}: in the docs, not read: {unharvested or '-'}; read, not in the docs: "
                f"{undocumented or '-'}"
            )


if __name__ == "__main__":
    sys.exit(main())
