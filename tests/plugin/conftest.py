"""Shared helpers for the Mitsuba plugin tests (run by `make test` after the plugin build).

The oracle for the plugin's values is the Rust kernel reached through the `matte` binary
(`matte brdf --pairs`), a separate process built from the same sources, and Mitsuba's own
built-in plugins and `mitsuba.chi2` where they apply.
"""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from matte_mitsuba import registry

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
# The installed `matte` command of the environment running the tests (the checkout's .venv,
# where `make` installs the wheel): the tool as users run it, finding its Mitsuba side there.
MATTE = os.path.join(os.path.dirname(sys.executable), "matte")
SCENES = os.path.join(REPO, "mitsuba_scenes")


def releases(platform="linux-x86_64"):
    """The Mitsuba releases of cpp/mitsuba_releases.txt with a layer for `platform` (a column
    of the table; `-`: Mitsuba publishes no wheel there), oldest first."""
    rows = [line.split() for line in open(os.path.join(REPO, "cpp", "mitsuba_releases.txt"))]
    column = next(cols for cols in rows if cols[:2] == ["#", "release"]).index(platform) - 1
    return [cols[0] for cols in rows if cols and cols[0][0].isdigit() and cols[column] != "-"]


#: The Mitsuba release of the checkout's environment (setup/requirements.txt), the newest.
CHECKOUT_MITSUBA = next(
    line.split("==")[1].strip()
    for line in open(os.path.join(REPO, "setup", "requirements.txt"))
    if line.startswith("mitsuba==")
)


def _value(text):
    try:
        return float(text)
    except ValueError:
        return text


# (type, parameters) exercised by the agreement, χ² and finiteness tests: every registered
# model (the installed package's registry) that builds from its defaults, at its defaults and
# at each of its declared examples (every option).
CONFIGS = [
    (m["name"], params)
    for m in registry.MODELS
    if registry.builds_from_defaults(m)
    for params in [{}] + [{k: _value(v) for k, v in ex.items()} for ex in registry.examples(m)]
]


def config_id(cfg):
    kind, params = cfg
    return kind + "".join(f"-{k}={v}" for k, v in params.items())


def kernel_f(kind, params, reflectance, wi, wo):
    """f (no cosine) from the Rust kernel via `matte brdf --pairs -`, for float32 (n, 3) arrays."""
    return kernel_f_pdf(kind, params, reflectance, wi, wo)[0]


def kernel_f_pdf(kind, params, reflectance, wi, wo):
    """f (no cosine) and the sampling density from the Rust kernel, as `kernel_f`."""
    lines = "\n".join(
        " ".join(repr(float(x)) for x in (*a, *b)) for a, b in zip(wi.astype(np.float32), wo.astype(np.float32))
    )
    args = [MATTE, "brdf", "--bsdf", kind, "--reflectance", repr(float(reflectance)), "--pairs", "-"]
    for k, v in params.items():
        args += ["--param", f"{k}={v}"]
    out = json.loads(subprocess.run(args, input=lines, capture_output=True, text=True, check=True).stdout)
    return np.array(out["f"], dtype=np.float64), np.array(out["pdf"], dtype=np.float64)


def random_pairs(n, seed):
    """float32 unit direction pairs; most above the surface, ~10 % with a direction below."""
    rng = np.random.default_rng(seed)

    def dirs(m):
        z = rng.uniform(-0.1, 1.0, m)
        phi = rng.uniform(0, 2 * np.pi, m)
        r = np.sqrt(np.maximum(0.0, 1 - z * z))
        return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1).astype(np.float32)

    return dirs(n), dirs(n)


@pytest.fixture
def mi_variant(request):
    """Sets the Mitsuba variant given by the test's parameter and imports matte_mitsuba, with
    Dr.Jit's default (symbolic) loops and calls."""
    import drjit as dr
    import mitsuba as mi

    mi.set_variant(request.param)
    import matte_mitsuba

    matte_mitsuba.register()
    assert dr.flag(dr.JitFlag.SymbolicLoops) and dr.flag(dr.JitFlag.SymbolicCalls)
    yield mi
