"""How the `matte` binary finds its Python side and package data (rust/matte/src/installation.rs; the
README's "Which Python runs Mitsuba's side"): `--python`, then `MATTE_PYTHON`, then the Python
of the environment matte belongs to, then `python3` on `PATH`, the first that can import
matte_mitsuba; when none can, one line saying what was tried and how to fix it.

The binary under test is the installed one copied to a folder of its own, so that it belongs
to no environment and only what each test gives it can be found."""

import json
import os
import shutil
import subprocess
import sys

import matte_mitsuba
import pytest

INSTALLED = os.path.join(matte_mitsuba.PACKAGE_ROOT, "bin", "matte")
# A Python without matte_mitsuba: the interpreter the test environment was made from.
BARE_PYTHON = getattr(sys, "_base_executable", None)


@pytest.fixture
def lone_matte(tmp_path):
    folder = tmp_path / "bin"
    folder.mkdir()
    copy = folder / "matte"
    shutil.copy(INSTALLED, copy)
    return str(copy)


def run(matte, *args, env, cwd):
    return subprocess.run([matte, *args], capture_output=True, text=True, env=env, cwd=cwd, timeout=600)


def error_line(r):
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1, (r.returncode, r.stderr)
    return lines[0]


def test_without_any_python_the_error_is_one_line_with_the_fix(lone_matte, tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    r = run(lone_matte, "validate", "--all", env={"PATH": str(empty)}, cwd=tmp_path)
    line = error_line(r)
    assert line.startswith("matte: error: "), line
    assert (
        "no Python with matte_mitsuba found (no --python, no MATTE_PYTHON, no python3 beside matte or on PATH)" in line
    )
    assert "pip install matte-mitsuba" in line and "--python PATH or MATTE_PYTHON" in line, line


def test_a_python3_on_path_that_cannot_import_matte_mitsuba_is_named_as_tried(lone_matte, tmp_path):
    if not BARE_PYTHON or BARE_PYTHON == sys.executable:
        pytest.skip("the tests do not run in a virtual environment: no Python without matte_mitsuba at hand")
    path = tmp_path / "path"
    path.mkdir()
    os.symlink(BARE_PYTHON, path / "python3")
    r = run(lone_matte, "validate", "scene.xml", env={"PATH": str(path)}, cwd=tmp_path)
    line = error_line(r)
    assert f"tried {path / 'python3'} (python3 on PATH): it cannot import matte_mitsuba" in line, line


def test_matte_python_is_used_as_given_and_named_when_it_fails(lone_matte, tmp_path):
    env = {"PATH": os.environ["PATH"], "MATTE_PYTHON": str(tmp_path / "no_such_python")}
    line = error_line(run(lone_matte, "validate", "--all", env=env, cwd=tmp_path))
    assert line.startswith("matte: error: ") and f"MATTE_PYTHON={tmp_path / 'no_such_python'}: cannot run it" in line, (
        line
    )
    if BARE_PYTHON and BARE_PYTHON != sys.executable:
        env["MATTE_PYTHON"] = BARE_PYTHON
        line = error_line(run(lone_matte, "validate", "--all", env=env, cwd=tmp_path))
        assert (
            line == f"matte: error: matte's package data (scenes, tables) comes with matte_mitsuba: "
            f"MATTE_PYTHON={BARE_PYTHON}: it cannot import matte_mitsuba"
        ), line


def test_the_python_option_wins_and_finds_mitsuba_and_the_bundled_scenes(lone_matte, tmp_path):
    # MATTE_PYTHON names nothing usable; --python names this environment, which has everything.
    env = {"PATH": os.environ["PATH"], "MATTE_PYTHON": str(tmp_path / "no_such_python")}
    r = run(
        lone_matte,
        "--python",
        sys.executable,
        "validate",
        "sphere_lambert",
        "--quick",
        "-D",
        "res=8",
        "-q",
        "--json",
        "-o",
        "out",
        env=env,
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    summary = json.loads(r.stdout)
    provenance = summary["provenance"]
    assert provenance["python"].startswith(f"{sys.executable} (--python), Mitsuba {provenance['mitsuba']}"), provenance
    # The bare name is the bundled scene of the package that Python holds.
    assert summary["scenes"][0]["scene"] == os.path.join(matte_mitsuba.SCENES, "sphere_lambert.xml")


def test_the_binary_inside_an_environment_finds_that_environment(tmp_path):
    # The installed binary, run directly (not through the `matte` command), with nothing on
    # PATH: it belongs to this environment, whose python3 it finds.
    empty = tmp_path / "empty"
    empty.mkdir()
    r = run(
        INSTALLED,
        "validate",
        "sphere_lambert",
        "--quick",
        "-D",
        "res=8",
        "-q",
        "--json",
        "-o",
        "out",
        env={"PATH": str(empty)},
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    assert "(the environment matte is installed in)" in r.stdout, r.stdout[:2000]
