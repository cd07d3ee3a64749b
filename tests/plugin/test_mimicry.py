"""validation/experiments/mimicry.py (the model-mimicry table): its error measures against closed forms, and
one diagonal cell end to end: EON fitted to an EON target on the sphere recovers the
parameters the target was rendered with (the study's r = 0.3 and the sphere's reflectance, the
oracle), and its residual stays near the noise floor. About 20 s.
"""

import json
import os

import numpy as np
import pytest

from validation.experiments import mimicry

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture
def image():
    return np.random.default_rng(7).uniform(0.2, 1.0, (16, 16, 3))


def test_relative_rmse_and_worst_region_of_a_uniform_scale(image):
    scaled = 1.03 * image
    assert mimicry.relative_rmse([scaled], [image]) == pytest.approx(0.03, rel=1e-9)
    err, c, i, j = mimicry.worst_region([scaled], [image])
    assert err == pytest.approx(0.03, rel=1e-9) and c == 0


def test_worst_region_finds_the_changed_block_and_skips_dark_ones(image):
    changed = image.copy()
    changed[8:16, 0:8] *= 1.1  # block (1, 0) of 8x8 pixels (two blocks per side): +10 %
    assert mimicry.worst_region([image, changed], [image, image], blocks=2) == (pytest.approx(0.1, rel=1e-9), 1, 1, 0)
    dark = image.copy()
    dark[0:8, 8:16] = 1e-3  # far below 25 % of the mean block: skipped even when doubled
    assert mimicry.worst_region([np.where(dark < 0.01, 2 * dark, dark)], [dark], blocks=2)[0] == 0.0


def test_excess_above_the_noise_floor():
    assert mimicry.excess(0.05, 0.03) == pytest.approx(0.04)
    assert mimicry.excess(0.02, 0.03) == 0.0


def test_a_model_fitted_to_its_own_target_recovers_its_parameters(tmp_path):
    out = tmp_path / "out"
    assert (
        mimicry.main(
            [
                "-o",
                str(out),
                "--scenes",
                "sphere",
                "--models",
                "eon",
                "--res",
                "32",
                "--iterations",
                "50",
                "--spp",
                "8",
                "--target-spp",
                "512",
                "--start",
                "eon=0.6",
            ]
        )
        == 0
    )
    summary = json.loads((out / "mimicry.json").read_text())
    scene = summary["scenes"]["sphere"]
    cell = scene["cells"]["eon"]["eon"]
    r = cell["fitted"]["ball.bsdf.roughness"][0]
    rho = cell["fitted"]["ball.bsdf.reflectance.value"]
    floor = scene["noise_floor"]["eon"]["relative_rmse"]
    print(
        f"fitted r {r:.4f} (truth 0.3, start 0.6), rho {np.round(rho, 4)}, rel. RMSE {cell['relative_rmse']:.4f} "
        f"(floor {floor:.4f})"
    )
    assert abs(r - mimicry.SHAPE["eon"][1]) < 0.05, r
    assert np.allclose(rho, [0.8, 0.6, 0.4], atol=0.03), rho
    assert cell["relative_rmse"] < 1.5 * floor
    for f in ("index.html", "sphere/grid.png", "sphere/eon/eon.png", "sphere/eon/eon/index.html"):
        assert (out / f).stat().st_size > 0, f
