"""The debug and test builds' optimisation list (Cargo.toml, `[profile.dev.package]`): every
dependency at opt-level 3 except the crates that only run while building (proc macros, build
scripts and what they use), which are named at opt-level 0. A crate named there that the
program also links would run unoptimised; a build-time crate left out would be compiled at
opt-level 3 for nothing. Both sets come from `cargo tree`: the build-time crates are those
reached only through build or proc-macro edges.

The release build (`[profile.release.package]`) lowers a few linked crates that never run on a
render's path; none of them may be a dependency of the kernels' crate."""

import subprocess
from pathlib import Path

import tomllib

ROOT = Path(__file__).resolve().parents[2]


def crates(*edges, package=None):
    out = subprocess.run(
        [
            "cargo",
            "tree",
            *(["-p", package] if package else ["--workspace"]),
            "--target",
            "all",
            "--prefix",
            "none",
            "--format",
            "{p}",
            "-e",
            ",".join(edges),
        ],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    return {line.split()[0] for line in out.splitlines() if line.strip()}


def test_build_time_crates_are_exactly_those_at_opt_level_0():
    profile = tomllib.loads((ROOT / "Cargo.toml").read_text())["profile"]["dev"]["package"]
    assert profile.pop("*") == {"opt-level": 3}
    named = {name for name, settings in profile.items() if settings == {"opt-level": 0}}
    assert named == set(profile), "every named package is at opt-level 0"
    run_time = crates("normal", "dev", "no-proc-macro")
    build_only = crates("all") - run_time
    assert len(build_only) > 10 and "syn" in build_only and "glam" in run_time
    assert sorted(named - build_only) == [], "linked into the program, so optimised"
    assert sorted(build_only - named) == [], "only run while building: add at opt-level 0"
    # The test build lowers only the crates above the kernels: the kernels' statistical sweeps
    # and every dependency stay optimised.
    lowered = tomllib.loads((ROOT / "Cargo.toml").read_text())["profile"]["test"].get("package", {})
    assert "matte-brdf" not in lowered and "*" not in lowered, lowered


def test_a_library_without_a_test_harness_has_no_tests():
    """`test = false` (Cargo.toml's [lib]) saves compiling a crate a second time for a harness
    it does not need: only while its sources hold no #[test] and no doctest."""
    manifest = tomllib.loads((ROOT / "Cargo.toml").read_text())
    lib = manifest["lib"]
    assert lib.get("test") is False and lib.get("doctest") is False
    src = (ROOT / lib["path"]).parent
    sources = [p.read_text() for p in src.rglob("*.rs")]
    assert len(sources) > 2
    assert not [s for s in sources if "#[test]" in s or "```" in s]


def test_the_release_builds_unoptimised_crates_are_linked_and_not_the_kernels():
    lowered = tomllib.loads((ROOT / "Cargo.toml").read_text())["profile"]["release"]["package"]
    assert all(settings == {"opt-level": 0} for settings in lowered.values()), lowered
    run_time = crates("normal", "no-proc-macro")
    kernels = crates("normal", "no-proc-macro", package="matte-brdf")
    assert "glam" in kernels and "moxcms" in run_time
    assert sorted(set(lowered) - run_time) == [], "not linked: nothing to lower"
    assert sorted(set(lowered) & kernels) == [], "the kernels' dependencies stay optimised"
