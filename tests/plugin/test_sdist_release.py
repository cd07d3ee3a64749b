"""A Mitsuba release matte's table does not know, built from the sdist: in a copy of the sdist
of `make dist` with 3.8.0 hidden from cpp/mitsuba_releases.txt, `pip wheel` (pip's default
build isolation) in the 3.8.0 environment of the release matrix builds a layer for the
installed 3.8.0 from the headers of its own wheel (its Dr.Jit release and instruction set read
from there). That wheel, put first on the path of the same environment, must load under 3.8.0
and agree with the release wheel's layer for 3.8.0 (which the table built from 3.8.0's
downloaded wheels): values to 1e-5 relative, the render within noise, one gradient. The build
shares the checkout's cargo target folder and builds the table's layer for the newest release only
(MATTE_MITSUBA_RELEASES), so that it takes seconds, not the whole release list."""

import glob
import json
import os
import shutil
import subprocess
import tarfile
import zipfile

import numpy as np
from conftest import REPO, releases
from test_releases import python_of, release_check, run_check

HIDDEN = "3.8.0"
NEWEST = releases()[-1]


def test_a_hidden_release_builds_from_the_sdist_and_agrees_with_the_wheel(tmp_path):
    subprocess.run([os.path.join(REPO, "setup", "release_venvs.sh")], check=True)
    (sdist,) = glob.glob(os.path.join(REPO, "dist", "matte_mitsuba-*.tar.gz"))
    with tarfile.open(sdist) as t:
        t.extractall(tmp_path, filter="data")
    (source,) = glob.glob(str(tmp_path / "matte_mitsuba-*"))
    table = os.path.join(source, "cpp", "mitsuba_releases.txt")
    lines = open(table).read().splitlines(keepends=True)
    with open(table, "w") as f:
        f.writelines(line for line in lines if not line.startswith(HIDDEN + " "))

    python = python_of(HIDDEN)
    env = {**os.environ, "MATTE_MITSUBA_RELEASES": NEWEST, "CARGO_TARGET_DIR": os.path.join(REPO, "target")}
    built = tmp_path / "wheel"
    r = subprocess.run(
        [python, "-m", "pip", "wheel", source, "--no-deps", "-w", str(built), "-q", "--disable-pip-version-check"],
        capture_output=True,
        text=True,
        env=env,
    )
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-4000:]
    (wheel,) = glob.glob(str(built / "*.whl"))
    with zipfile.ZipFile(wheel) as z:
        build = z.read("matte_mitsuba/_build.py").decode()
        metadata = z.read(next(n for n in z.namelist() if n.endswith("METADATA"))).decode()
        assert f"matte_mitsuba/releases/{HIDDEN}/plugins/libmatte_bsdfs.so" in z.namelist()
    assert f'MITSUBA_RELEASES = ("{HIDDEN}", "{NEWEST}",)' in build, build.splitlines()[:3]
    assert f"Requires-Dist: mitsuba<={NEWEST},>={HIDDEN}" in metadata

    # The built wheel first on the path of the 3.8.0 environment, which holds the release wheel.
    site = tmp_path / "site"
    subprocess.run([python, "-m", "pip", "install", "-q", "--no-deps", "--target", str(site), wheel], check=True)
    shim = tmp_path / "python"
    shim.write_text(f'#!/bin/sh\nPYTHONPATH="{site}" exec "{python}" "$@"\n')
    shim.chmod(0o755)
    where = subprocess.run(
        [str(shim), "-c", "import matte_mitsuba; print(matte_mitsuba.PLUGIN_ROOT)"], capture_output=True, text=True
    )
    assert where.stdout.strip() == os.path.join(str(site), "matte_mitsuba", "releases", HIDDEN), where.stderr

    for variant in ("scalar_rgb", "llvm_ad_rgb"):
        got, ref = release_check(str(shim), HIDDEN, "values", variant), run_check(HIDDEN, "values", variant)
        for kind, v in got["types"].items():
            for q in ("f", "pdf"):
                a, b = np.array(v[q]), np.array(ref["types"][kind][q])
                gap = (np.abs(a - b) / np.maximum(np.abs(b), 1e-6)).max()
                assert gap <= 1e-5, f"{kind} {q} ({variant}): the sdist's layer differs from the wheel's by {gap:.2e}"
    got = np.array(release_check(str(shim), HIDDEN, "render", "llvm_ad_rgb")["image"])
    ref = np.array(run_check(HIDDEN, "render", "llvm_ad_rgb")["image"])
    d = got - ref
    assert np.isfinite(got).all() and abs(d.mean()) <= 4 * d.std(ddof=1) / np.sqrt(d.size) + 1e-6
    g = release_check(str(shim), HIDDEN, "gradient", "ginneken")["types"]["ginneken"]
    w = run_check(HIDDEN, "gradient")["types"]["ginneken"]
    print(json.dumps({"sdist": g, "wheel": w}))
    assert abs(g["ad"] - g["fd"]) <= 0.01 * abs(g["fd"]) and abs(g["ad"] - w["ad"]) <= 1e-3 * abs(w["ad"]), (g, w)
    shutil.rmtree(site)
