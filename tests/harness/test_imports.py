"""The crates' import structure (validation/check_imports.py): no two files of a crate import each
other, and no crate but matte-render has a longer circle (the renderer's scene, loader and plugin
families still reach each other through the loader). The checker itself is tested on a small
crate written here, so that a checker that finds nothing cannot pass."""

from pathlib import Path

import pytest

from validation import check_imports

ROOT = Path(__file__).resolve().parents[2]
CRATES = sorted(p.parent.name for p in (ROOT / "rust").glob("*/src"))
# The crates allowed a circle longer than a pair.
CIRCLES_ALLOWED = {"render"}


def pairs(edges):
    return sorted((a, b) for a in edges for b in edges[a] if a < b and a in edges.get(b, ()))


@pytest.mark.parametrize("crate", CRATES)
def test_no_two_files_import_each_other(crate):
    edges = check_imports.graph(ROOT / "rust" / crate / "src")
    assert len(edges) > 1, crate
    assert pairs(edges) == [], crate
    if crate not in CIRCLES_ALLOWED:
        assert check_imports.circles(edges) == [], crate


def test_the_checker_finds_a_pair_and_a_circle(tmp_path):
    src = tmp_path / "src"
    (src / "a").mkdir(parents=True)
    (src / "lib.rs").write_text("mod a;\nmod b;\nmod c;\n")
    (src / "a" / "mod.rs").write_text("mod x;\npub use x::X;\npub struct A;\n")
    (src / "a" / "x.rs").write_text("use super::A;\npub struct X;\n")  # x <-> a/mod.rs
    (src / "b.rs").write_text("use crate::c::C;\npub struct B;\n")
    (src / "c.rs").write_text("use crate::b::B;\npub struct C;\n")
    edges = check_imports.graph(src)
    found = {(a.relative_to(src).as_posix(), b.relative_to(src).as_posix()) for a, b in pairs(edges)}
    assert found == {("a/mod.rs", "a/x.rs"), ("b.rs", "c.rs")}
