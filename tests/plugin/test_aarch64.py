"""The Linux aarch64 wheel of `make dist` (cross-built on this x86-64 machine), run under
emulation: qemu-user with Debian's arm64 Python 3.11 and libLLVM 19, beside Mitsuba's aarch64
wheels of the oldest release that has them and the newest (the table's linux-aarch64 column;
setup/aarch64_env.sh makes the environments once and installs the wheel anew).

* values: f·cos and pdf of every type in scalar_rgb and llvm_ad_rgb (symbolic loop) equal the
  x86-64 build's under this environment's Mitsuba to 1e-5 relative;
* render: the Cornell box (wolff, ginneken, eon) in llvm_ad_rgb equals the x86-64 build's
  render within noise;
* gradient: ginneken's roughness, prb's adjoint equal to central differences within 1 %;
* chi2: Mitsuba's χ² test accepts ginneken's sampler;
* `matte validate`: the aarch64 `matte` binary of the wheel (its own renderer, which falls back
  to its own BVH without Embree) with its Mitsuba side in the emulated Python passes a bundled
  scene.

The checks of the native matrix (tests/plugin/test_releases.py) are the same code
(release_checks.py), so a difference here is the platform's."""

import functools
import glob
import os
import subprocess
import sys

import numpy as np
import pytest
from conftest import REPO, releases
from release_checks import variant_of
from test_releases import release_check, release_checks

RELEASES = [releases("linux-aarch64")[0], releases("linux-aarch64")[-1]]


@functools.lru_cache(maxsize=None)
def environment():
    wheels = glob.glob(os.path.join(REPO, "dist", "matte_mitsuba-*manylinux*_aarch64.whl"))
    assert len(wheels) == 1, f"expected one aarch64 wheel of `make dist` in dist/, found {wheels}"
    r = subprocess.run(
        [os.path.join(REPO, "setup", "aarch64_env.sh"), wheels[0], *RELEASES],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    return r.stdout.strip().splitlines()[-1]


# The emulated checks, one process per release and variant (each emulated Python takes seconds to
# start): what the tests below ask of each.
EMULATED = {
    "scalar_rgb": [("values", "scalar_rgb")],
    "llvm_ad_rgb": [
        ("platform",),
        ("values", "llvm_ad_rgb"),
        ("render", "llvm_ad_rgb"),
        ("gradient", "ginneken"),
        ("chi2",),
    ],
}


@functools.lru_cache(maxsize=None)
def emulated_batch(release, variant):
    python = os.path.join(environment(), "bin", f"python-{release}")
    return release_checks(python, release, EMULATED[variant])


def emulated(release, check, *args):
    return emulated_batch(release, variant_of(check, args[0] if args else None))[(check, *args)]


@functools.lru_cache(maxsize=None)
def native(check, *args):
    import mitsuba

    return release_check(sys.executable, mitsuba.__version__, check, *args)


@pytest.mark.parametrize("release", RELEASES)
def test_the_environment_is_aarch64(release):
    where = emulated(release, "platform")
    assert where["machine"] == "aarch64", where
    assert where["plugin_root"].endswith(os.path.join("releases", release)), where


@pytest.mark.parametrize("variant", ["scalar_rgb", "llvm_ad_rgb"])
@pytest.mark.parametrize("release", RELEASES)
def test_values_equal_the_x86_64_build(release, variant):
    got, ref = emulated(release, "values", variant), native("values", variant)
    assert got["types"].keys() == ref["types"].keys()
    for kind, v in got["types"].items():
        for q in ("f", "pdf"):
            a, b = np.array(v[q], dtype=np.float64), np.array(ref["types"][kind][q], dtype=np.float64)
            assert np.isfinite(a).all(), (kind, q)
            gap = (np.abs(a - b) / np.maximum(np.abs(b), 1e-6)).max()
            assert gap <= 1e-5, f"{kind} {q}: aarch64 under Mitsuba {release} differs from x86-64 by {gap:.2e}"


@pytest.mark.parametrize("release", RELEASES)
def test_llvm_render_equals_the_x86_64_render_within_noise(release):
    got = np.array(emulated(release, "render", "llvm_ad_rgb")["image"])
    ref = np.array(native("render", "llvm_ad_rgb")["image"])
    assert np.isfinite(got).all()
    d = got - ref
    se = d.std(ddof=1) / np.sqrt(d.size)
    print(
        f"aarch64, Mitsuba {release}: mean {got.mean():.5f}, x86-64 {ref.mean():.5f}, difference {d.mean():.2e} ± {se:.1e}"
    )
    assert ref.mean() > 0.05 and abs(d.mean()) <= 4 * se + 1e-6, (d.mean(), se)


@pytest.mark.parametrize("release", RELEASES)
def test_gradient_equals_central_differences(release):
    g = emulated(release, "gradient", "ginneken")["types"]["ginneken"]
    print(f"aarch64, Mitsuba {release}: ginneken d(mean)/d({g['parameter']}): AD {g['ad']:.6g}  FD {g['fd']:.6g}")
    assert np.isfinite(g["ad"]) and abs(g["fd"]) > 1e-6, g
    assert abs(g["ad"] - g["fd"]) <= 0.01 * abs(g["fd"]), g


@pytest.mark.parametrize("release", RELEASES)
def test_chi2_accepts_ginnekens_sampler(release):
    result = emulated(release, "chi2")
    assert result["passed"], result["messages"]


def test_matte_validate_passes_a_bundled_scene(tmp_path):
    env = environment()
    release = RELEASES[-1]
    matte = os.path.join(env, f"site-{release}", "matte_mitsuba", "bin", "matte")
    r = subprocess.run(["file", "-b", matte], capture_output=True, text=True)
    assert "aarch64" in r.stdout, r.stdout
    out = tmp_path / "validate"
    cmd = [os.path.join(env, "bin", "qemu"), matte, "--python", os.path.join(env, "bin", f"python-{release}")]
    r = subprocess.run(
        cmd + ["validate", "sphere_wolff", "--quick", "-D", "res=16", "-q", "-o", str(out)],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-3000:]
    assert (out / "report.html").is_file()
