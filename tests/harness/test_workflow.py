"""The GitHub workflow (.github/workflows/wheels.yml) cannot run here; what it runs can be checked:
it builds on a native machine of every platform of cpp/build_plugin.py, and every command it
runs is one the Makefile provides (a `make` target, or a recipe's command with `$(PY)` as `$PY`),
or a set-up step of the runner (packages, Rust, Python), with the versions setup/requirements.txt
pins."""

import os
import re
import shlex
import sys

import pytest

yaml = pytest.importorskip("yaml")

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "cpp"))
import build_plugin  # noqa: E402

WORKFLOW = os.path.join(REPO, ".github", "workflows", "wheels.yml")
# First words of the runner's own set-up (installing packages and toolchains, exporting paths).
SETUP = {"apt-get", "curl", "echo", "brew", "python3"}


def workflow():
    with open(WORKFLOW) as f:
        return yaml.safe_load(f)


def makefile():
    text = open(os.path.join(REPO, "Makefile")).read()
    targets = set(re.findall(r"^([a-z][\w-]*):", text, re.M))
    recipes = [line.strip().lstrip("@") for line in text.splitlines() if line.startswith("\t")]
    return targets, recipes


def commands():
    """(job, command) for every command of every `run:` step."""
    for name, job in workflow()["jobs"].items():
        for step in job["steps"]:
            for line in step.get("run", "").splitlines():
                for part in line.split("&&"):
                    if part.strip():
                        yield name, part.strip()


def pins():
    return dict(
        line.split("==")
        for line in open(os.path.join(REPO, "setup", "requirements.txt")).read().split("\n")
        if "==" in line and not line.startswith("#")
    )


def test_every_platform_has_a_native_job():
    jobs = workflow()["jobs"]
    native = {entry["platform"]: entry["os"] for entry in jobs["native"]["strategy"]["matrix"]["include"]}
    assert set(native) | {"linux-x86_64"} == set(build_plugin.PLATFORMS), native
    assert jobs["linux-x86_64"]["runs-on"].startswith("ubuntu-") and "-arm" not in jobs["linux-x86_64"]["runs-on"]
    assert native["linux-aarch64"].endswith("-arm") and native["macos-arm64"].startswith("macos-")
    assert native["windows-x86_64"].startswith("windows-")


def test_every_command_is_the_makefiles_or_the_runners_set_up():
    targets, recipes = makefile()
    required = pins()
    seen = set()
    for job, command in commands():
        words = shlex.split(command)
        env = [w for w in words if re.fullmatch(r"[A-Z_]+=\S*", w)]
        words = words[len(env) :]
        if words[0] == "make":
            assert all(t in targets for t in words[1:]), (job, command)
            seen.add("make")
        elif words[0] == "$PY":
            rest = command.split("$PY", 1)[1].strip()
            if rest.startswith("-m pip install -q ") and "==" in rest:
                for pin in words[5:]:
                    name, version = pin.split("==")
                    assert required.get(name) == version, (pin, required.get(name))
            elif rest.startswith("-m pip install --force-reinstall"):
                assert any(r.startswith("$(PY) " + rest.rsplit(" ", 1)[0]) for r in recipes), command
            else:
                assert any(r == "$(PY) " + rest or r.startswith("$(PY) " + rest + " ") for r in recipes) or (
                    rest.startswith("-m pytest") and any(r.startswith("$(PY) -m pytest") for r in recipes)
                ), command
                for path in (w for w in words if w.startswith("tests/")):
                    assert os.path.exists(os.path.join(REPO, path)), path
            seen.add("$PY")
        else:
            assert words[0] in SETUP or command.startswith("python3 -m venv"), (job, command)
        for variable in env:
            name = variable.split("=")[0]
            found = any(
                name in open(os.path.join(root, f)).read()
                for root, _, files in os.walk(os.path.join(REPO, "tests"))
                for f in files
                if f.endswith(".py")
            )
            assert found, f"{variable}: no test reads {name}"
    assert seen == {"make", "$PY"}, seen


def test_the_checker_refuses_a_command_the_makefile_does_not_have():
    targets, recipes = makefile()
    assert "dist" in targets and "nonexistent" not in targets
    wheel = "-m pip wheel . --no-deps --no-build-isolation -w dist -q --disable-pip-version-check"
    assert any(r.startswith("$(PY) " + wheel) for r in recipes)
    assert not any(r.startswith("$(PY) -m pip wheel . --build-isolation") for r in recipes)
