"""The Mitsuba release matrix: the wheel of `make dist` installed beside each release of
cpp/mitsuba_releases.txt, each in its own environment (`.venvs/mitsuba-<release>`, made once and
reused by setup/release_venvs.sh, which installs the current wheel into each), where
tests/plugin/release_checks.py runs the plugin's core checks, one process per check:

* values: f·cos and pdf of every registered type on 256 fixed direction pairs, in scalar_rgb
  and in llvm_ad_rgb inside a symbolic loop, equal the Rust kernel (`matte brdf --pairs`) to
  1e-5 relative, and equal the values under 3.9.1 to 1e-5;
* render: the Cornell box in wolff, ginneken and eon renders in llvm_ad_rgb (symbolic) equal to
  scalar_rgb within noise (the mean pixel difference within 4 standard errors), finite;
* gradient: one parameter per type (the first numeric one, else the reflectance), prb's
  adjoint equal to central differences within 1 %;
* chi2: Mitsuba's χ² test accepts ginneken's sampler at 45° incidence.

Under Mitsuba 3.6.4, the release before the oldest supported one, importing matte_mitsuba fails
with one line naming the supported releases."""

import functools
import json
import os
import subprocess
import sys

import numpy as np
import pytest
from conftest import REPO, kernel_f_pdf, releases
from release_checks import RGB

# MATTE_RELEASE_MATRIX=installed: the checks under the environment running the tests only (the
# wheel built on this machine installed beside one Mitsuba): the workflow's native jobs on
# macOS, Windows and Linux aarch64 (.github/workflows/wheels.yml), where no release matrix is set up.
INSTALLED = os.environ.get("MATTE_RELEASE_MATRIX") == "installed"
RELEASES = [__import__("mitsuba").__version__] if INSTALLED else releases()
NEWEST = RELEASES[-1]
UNSUPPORTED = "3.6.4"
needs_matrix = pytest.mark.skipif(INSTALLED, reason="needs the release matrix (MATTE_RELEASE_MATRIX=installed)")


@pytest.fixture(scope="module", autouse=True)
def environments():
    """Every release's environment, with the wheel `make dist` built installed."""
    if not INSTALLED:
        subprocess.run([os.path.join(REPO, "setup", "release_venvs.sh")], check=True)


def python_of(release):
    if INSTALLED:
        return sys.executable
    return os.path.join(REPO, ".venvs", f"mitsuba-{release}", "bin", "python")


def release_check(python, release, check, *args):
    """release_checks.py's `check` (with its arguments) run by `python`, under Mitsuba `release`."""
    return release_checks(python, release, [(check, *args)])[(check, *args)]


def release_checks(python, release, checks):
    """Several of release_checks.py's checks, each (check, *args), of one variant in one process
    run by `python` (where a process costs seconds to start): {(check, *args): result}."""
    script = os.path.join(REPO, "tests", "plugin", "release_checks.py")
    words = [":".join(c) for c in checks]
    r = subprocess.run([python, script, "--many", *words], capture_output=True, text=True, cwd=os.path.dirname(script))
    assert r.returncode == 0, f"Mitsuba {release}, {' '.join(words)}:\n{r.stderr[-3000:]}"
    results = json.loads(r.stdout.strip().splitlines()[-1])
    assert [x["mitsuba"] for x in results] == [release] * len(checks), results
    return dict(zip(checks, results))


@functools.lru_cache(maxsize=None)
def run_check(release, check, *args):
    return release_check(python_of(release), release, check, *args)


@functools.lru_cache(maxsize=None)
def kernel(kind, filename, channel):
    """f and pdf of the Rust kernel on release_checks' pairs (for one reflectance channel)."""
    pairs = run_check(NEWEST, "values", "scalar_rgb")
    wi, wo = np.array(pairs["wi"], dtype=np.float32), np.array(pairs["wo"], dtype=np.float32)
    f, pdf = kernel_f_pdf(kind, {"filename": filename} if filename else {}, RGB[channel], wi, wo)
    return f, pdf, wo


def relative_error(a, b):
    return np.abs(a - b) / np.maximum(np.abs(b), 1e-6)


@pytest.mark.parametrize("variant", ["scalar_rgb", "llvm_ad_rgb"])
@pytest.mark.parametrize("release", RELEASES)
def test_values_equal_the_kernel_and_the_newest_release(release, variant):
    got = run_check(release, "values", variant)
    newest = run_check(NEWEST, "values", variant)
    assert got["types"].keys() == newest["types"].keys()
    for kind, v in got["types"].items():
        f, pdf = np.array(v["f"]), np.array(v["pdf"])
        assert np.isfinite(f).all() and np.isfinite(pdf).all(), kind
        gap = max(
            np.abs(f - np.array(newest["types"][kind]["f"])).max(), np.abs(pdf - newest["types"][kind]["pdf"]).max()
        )
        assert gap <= 1e-5, f"{kind}: Mitsuba {release} differs from {NEWEST} by {gap:.2e}"
        filename = None
        if kind == "tabulated_brdf":
            filename = os.path.join(REPO, "python", "matte_mitsuba", "ground_truth", "v_cavities_sigma0.3.json")
        for c in range(3):
            kf, kpdf, wo = kernel(kind, filename, c)
            cos = wo[:, 2].astype(np.float64)
            plugin_f = np.where(cos > 0, f[:, c] / np.where(cos > 0, cos, 1.0), 0.0)
            assert relative_error(plugin_f, kf).max() <= 1e-5, f"{kind} channel {c}: f differs from the kernel"
        assert relative_error(pdf, kpdf).max() <= 1e-5, f"{kind}: pdf differs from the kernel"


@pytest.mark.parametrize("release", RELEASES)
def test_llvm_render_equals_scalar_within_noise(release):
    scalar = np.array(run_check(release, "render", "scalar_rgb")["image"])
    llvm = np.array(run_check(release, "render", "llvm_ad_rgb")["image"])
    assert np.isfinite(scalar).all() and np.isfinite(llvm).all()
    d = llvm - scalar
    se = d.std(ddof=1) / np.sqrt(d.size)
    print(
        f"Mitsuba {release}: mean llvm {llvm.mean():.5f}, scalar {scalar.mean():.5f}, difference {d.mean():.2e} ± {se:.1e}"
    )
    assert scalar.mean() > 0.05 and abs(d.mean()) <= 4 * se, (d.mean(), se)


@pytest.mark.parametrize("release", RELEASES)
def test_gradients_equal_central_differences(release):
    for kind, g in run_check(release, "gradient")["types"].items():
        ad, fd = g["ad"], g["fd"]
        print(f"Mitsuba {release} {kind} d(mean)/d({g['parameter']}): AD {ad:.6g}  FD {fd:.6g}")
        assert np.isfinite(ad) and abs(fd) > 1e-6, (kind, ad, fd)
        assert abs(ad - fd) <= 0.01 * abs(fd), f"{kind} {g['parameter']}: AD {ad} vs FD {fd}"


@pytest.mark.parametrize("release", RELEASES)
def test_chi2_accepts_ginnekens_sampler(release):
    result = run_check(release, "chi2")
    assert result["passed"], result["messages"]


@needs_matrix
def test_an_unsupported_release_is_refused_in_one_line():
    r = subprocess.run([python_of(UNSUPPORTED), "-c", "import matte_mitsuba"], capture_output=True, text=True, cwd="/")
    assert r.returncode != 0
    last = r.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: matte_mitsuba: Mitsuba 3.6.4 is installed"), r.stderr
    assert all(release in last for release in RELEASES), last
    assert "source distribution" not in last, "the sdist builds no layer for a release before the plugin API"


def test_a_newer_release_is_refused_naming_the_sdist():
    import matte_mitsuba

    with pytest.raises(ImportError) as e:
        matte_mitsuba._release_root("3.10.0")
    message = str(e.value)
    assert message.startswith("matte_mitsuba: Mitsuba 3.10.0 is installed") and "\n" not in message, message
    assert (
        "build matte for Mitsuba 3.10.0 from its source distribution (pip install matte_mitsuba-0.1.0.tar.gz" in message
    )
