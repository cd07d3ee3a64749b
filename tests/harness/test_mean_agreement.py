"""The Rust renderer against Mitsuba 3.9.1 scalar_rgb on bundled scenes: the image
mean per channel must agree within 3 standard errors. Each renderer renders the scene with
K independent seeds; the standard error of each renderer's mean comes from the spread of its
K image means, so the test needs no assumption about per-pixel noise or filter correlation.
The per-pixel statistical comparison is `matte validate`'s job.
"""

import json
import os
import subprocess
import sys
import tempfile

import matte_mitsuba  # noqa: F401  (puts matte's plugins on Mitsuba's search path)
import mitsuba as mi
import numpy as np
import pytest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
# The installed `matte` command of the environment running the tests (the checkout's .venv).
MATTE = os.path.join(os.path.dirname(sys.executable), "matte")
SCENES = os.path.join(REPO, "mitsuba_scenes")

K = 8
RES = 64
SPP = 64


def read_exr(path):
    mi.set_variant("scalar_rgb")
    bmp = mi.Bitmap(path)
    return np.array(bmp, dtype=np.float64)[..., :3]


def matte_means(scene, defines):
    means = []
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(K):
            out = os.path.join(tmp, f"{seed}.exr")
            cmd = [MATTE, "render", scene, "-o", out, "--spp", str(SPP), "--seed", str(1000 + seed), "--quiet"]
            for k, v in defines.items():
                cmd += ["-D", f"{k}={v}"]
            report = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
            assert report["invalid_samples"] == 0
            img = read_exr(out)
            assert np.isfinite(img).all()
            means.append(img.mean(axis=(0, 1)))
    return np.array(means)


def mitsuba_means(scene, defines):
    mi.set_variant("scalar_rgb")
    s = mi.load_file(scene, **defines)
    return np.array(
        [np.array(mi.render(s, spp=SPP, seed=seed), dtype=np.float64).mean(axis=(0, 1)) for seed in range(K)]
    )


@pytest.mark.parametrize(
    "scene, defines",
    [
        ("cornell_box.xml", {"res": RES}),
        # Every element matte renders: all shapes, lights, BSDFs incl. glass, metals, textures.
        ("features.xml", {}),
        # matte's numeric parameters as textures (σ, r, int_ior checkerboards and bitmaps).
        ("textured_parameters.xml", {"res": RES}),
    ],
)
def test_image_mean_agrees_with_mitsuba(scene, defines):
    path = os.path.join(SCENES, scene)
    a, b = matte_means(path, defines), mitsuba_means(path, defines)
    diff = a.mean(0) - b.mean(0)
    se = np.sqrt(a.var(0, ddof=1) / K + b.var(0, ddof=1) / K)
    z = diff / se
    print(f"matte {a.mean(0)} mitsuba {b.mean(0)} z {z}")
    assert (np.abs(z) < 3).all(), f"image means differ: matte {a.mean(0)}, mitsuba {b.mean(0)}, z = {z}"
    # The test has power: the relative standard error is small against a 2 % change.
    assert (se / b.mean(0) < 0.005).all(), f"too noisy to detect a 2 % difference: se {se}"
