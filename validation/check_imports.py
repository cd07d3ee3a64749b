#!/usr/bin/env python3
"""Import structure of one crate: which of its files import which (`use crate::…`, `use super::…`,
and a module's own children), the pairs of files that import each other, and every circle of
imports longer than a pair. Exits 1 if there is a pair or a circle.

    python3 validation/check_imports.py [rust/brdf/src]

A path resolves to the file of the deepest module it names (`crate::registry::spec::ParamSpec`:
`registry/spec.rs`; `crate::DiffuseModel`: `lib.rs`, the crate root)."""

import re
import sys
from pathlib import Path

USE = re.compile(r"^\s*(?:pub(?:\([^)]*\))?\s+)?use\s+([^;]+);", re.M)


def module_path(src: Path, file: Path) -> list[str]:
    """The module a file is (`registry/spec.rs`: ["registry", "spec"]; `lib.rs`: [])."""
    parts = list(file.relative_to(src).with_suffix("").parts)
    if parts[-1] in ("lib", "mod", "main"):
        parts.pop()
    return parts


def module_file(src: Path, path: list[str]) -> Path | None:
    """The file of module `path`, if there is one."""
    if not path:
        return src / "lib.rs"
    base = src.joinpath(*path)
    for f in (base.with_suffix(".rs"), base / "mod.rs"):
        if f.exists():
            return f
    return None


def expand(tree: str) -> list[str]:
    """The paths of a `use` tree (`a::{b, c::{d}}`: a::b, a::c::d)."""
    tree = re.sub(r"\s+", "", re.sub(r"\s+as\s+\w+", "", tree))
    depth, start = 0, None
    for i, ch in enumerate(tree):
        if ch == "{":
            if depth == 0:
                start = i
            depth += 1
        elif ch == "}":
            depth -= 1
            if depth == 0:
                prefix, inner, rest = tree[:start], tree[start + 1 : i], tree[i + 1 :]
                parts, d, s = [], 0, 0
                for j, c in enumerate(inner + ","):
                    if c == "{":
                        d += 1
                    elif c == "}":
                        d -= 1
                    elif c == "," and d == 0:
                        if inner[s:j]:
                            parts.append(inner[s:j])
                        s = j + 1
                return [p for part in parts for p in expand(prefix + part + rest)]
    return [tree]


def resolve(src: Path, here: list[str], is_mod_file: bool, path: str) -> Path | None:
    """The crate file a `use` path names, or None (another crate, std)."""
    segs = [s for s in path.split("::") if s and s not in ("self", "*")]
    if not segs:
        return None
    if segs[0] == "crate":
        base, rest = [], segs[1:]
    elif segs[0] == "super":
        base = here[:]
        rest = segs
        while rest and rest[0] == "super":
            base = base[:-1]
            rest = rest[1:]
    elif module_file(src, here + [segs[0]]) is not None and (is_mod_file or not here):
        base, rest = here[:], segs
    else:
        return None
    found = module_file(src, base)
    for k in range(len(rest)):
        f = module_file(src, base + rest[: k + 1])
        if f is None:
            break
        found = f
    return found


def graph(src: Path) -> dict[Path, set[Path]]:
    edges: dict[Path, set[Path]] = {}
    for file in sorted(src.rglob("*.rs")):
        here = module_path(src, file)
        is_mod_file = file.name in ("mod.rs", "lib.rs", "main.rs")
        text = re.sub(r"//[^\n]*", "", file.read_text())
        # Tests inside a file import their own module: not a dependency between files.
        text = re.split(r"#\[cfg\(test\)\]\s*mod\s+tests", text)[0]
        targets = set()
        for m in USE.finditer(text):
            for p in expand(m.group(1)):
                t = resolve(src, here, is_mod_file, p)
                if t is not None and t != file:
                    targets.add(t)
        edges[file] = targets
    return edges


def circles(edges: dict[Path, set[Path]]) -> list[list[Path]]:
    """The strongly connected components with more than one file (Tarjan)."""
    index, low, stack, on, out, n = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = n[0]
        n[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in list(edges):
        if v not in index:
            visit(v)
    return out


def main() -> int:
    src = Path(sys.argv[1] if len(sys.argv) > 1 else "rust/brdf/src")
    edges = graph(src)
    rel = lambda f: str(f.relative_to(src))  # noqa: E731
    pairs = sorted({tuple(sorted((rel(a), rel(b)))) for a, ts in edges.items() for b in ts if a in edges.get(b, ())})
    comps = circles(edges)
    print(f"{len(edges)} files, {sum(len(t) for t in edges.values())} imports between them")
    for a, b in pairs:
        print(f"pair: {a} <-> {b}")
    for c in comps:
        print("circle: " + ", ".join(rel(f) for f in c))
    if not pairs and not comps:
        print("no two files import each other; no circles")
    return 1 if pairs or comps else 0


if __name__ == "__main__":
    sys.exit(main())
