#!/usr/bin/env python3
"""Prints what Mitsuba 3.9.1 (scalar_rgb) gives for the inline oracles of tests/render/film.rs and
checks them against the numbers the test holds. Run by hand with the venv's Python from the
repository root (5–10 s, the edge renders):

    .venv/bin/python tests/render/film/generate_reference.py

Covered (test constant or function → what Mitsuba is asked):

* `gaussian_table.json` / `gaussian_table_matches_mitsuba`: the default `gaussian` filter's
  table, `rfilter.eval_discretized(r·(k + ½)/31)` for k = 0..30 (the middle of bin k), printed
  in the test's layout (5 decimals) and compared at those decimals; its radius.
* `mitchell_catmullrom_lanczos_match_mitsuba`: `rfilter.eval(x)` and `eval_discretized(x)` of
  `mitchell` (default B = C = 1/3, and B = 0.2, C = 0.4), `catmullrom`, `lanczos` (lobes 3 and
  2), to the test's 2e-6; their radii.
* `border_sizes_follow_mitsuba`: `rfilter.border_size()`.
* `tent_table_is_the_left_endpoint_discretisation`: the `tent` table is 1 − k/31.
* `gaussian_fit_is_the_minimax_approximation`: Mitsuba's `gaussian.eval` is within 4.2e-4 of
  exp(−2x²) − exp(−8).
* `half_bright_half_dark_edge_matches_mitsuba`: the 8×2 render of an emitter covering the left
  half of the view (perspective camera, default Gaussian filter, `path` max_depth 1), mean of
  32 independent renders of 65536 spp; the two pixels next to the edge, to the test's 2e-3
  (standard error ~6e-5). Mitsuba gives 0.83389 / 0.16611 (left + right = 1, as the mirror
  symmetry of the scene demands), which the test and docs/renderer-semantics.md §6 hold.

Prints one line per check and exits 1 if any differs.
"""

import json
import sys
from pathlib import Path

import mitsuba as mi
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "common"))
from reference_check import check, finish  # noqa: E402

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)


# The gaussian table the tests hold (gaussian_table.json beside this script), 5 decimals.
TEST_GAUSSIAN_TABLE = json.loads((Path(__file__).parent / "gaussian_table.json").read_text())["values"]


def table(f):
    r = f.radius()
    return [f.eval_discretized(r * (k + 0.5) / 31) for k in range(31)]


gauss = mi.load_dict({"type": "gaussian"})
values = table(gauss)
print("gaussian table (gaussian_table.json's values):", json.dumps([round(v, 5) for v in values]))
check("gaussian table, 5 decimals", np.round(values, 5), TEST_GAUSSIAN_TABLE)
check("gaussian radius", gauss.radius(), 2.0)
check("gaussian beyond the radius", gauss.eval_discretized(2.0), 0.0)

# mitchell_catmullrom_lanczos_match_mitsuba: (XML, radius, eval at XS, table at TABLE_XS)
XS = [0.0, 0.3, 0.75, 1.0, 1.4, 1.9, 2.5]
TABLE_XS = [0.0, 0.3, 1.4]
NEGATIVE_LOBED = [
    (
        {"type": "mitchell"},
        2.0,
        [0.888889, 0.740389, 0.2560764, 0.0555556, -0.0359999, -0.0029442, 0.0],
        [0.888889, 0.7757451, -0.0343129],
    ),
    (
        {"type": "mitchell", "B": 0.2, "C": 0.4},
        2.0,
        [0.9333333, 0.7704333, 0.2442707, 0.0333332, -0.0504004, -0.003567, 0.0],
        [0.9333333, 0.8091616, -0.0501273],
    ),
    ({"type": "catmullrom"}, 2.0, [1.0, 0.8155, 0.2265625, 0.0, -0.072, -0.0045002, 0.0], [1.0, 0.8592864, -0.0738479]),
    (
        {"type": "lanczos"},
        3.0,
        [1.0, 0.8443431, 0.2701898, 0.0, -0.1466851, -0.0237699, 0.0243171],
        [1.0, 0.8537122, -0.1469572],
    ),
    (
        {"type": "lanczos", "lobes": 2},
        2.0,
        [1.0, 0.8269746, 0.2353467, 0.0, -0.0795496, -0.0027135, 0.0],
        [1.0, 0.8697127, -0.0841129],
    ),
]
for d, radius, evals, tab in NEGATIVE_LOBED:
    f = mi.load_dict(d)
    name = ", ".join(f"{k}={v}" for k, v in d.items() if k != "type")
    name = f"{d['type']}({name})"
    check(f"{name} radius", f.radius(), radius)
    check(f"{name} eval at {XS}", [f.eval(x) for x in XS], evals, 2e-6)
    check(f"{name} eval_discretized at {TABLE_XS}", [f.eval_discretized(x) for x in TABLE_XS], tab, 2e-6)

# border_sizes_follow_mitsuba
for d, border in [
    ({"type": "box"}, 0),
    ({"type": "tent"}, 1),
    ({"type": "tent", "radius": 0.5}, 0),
    ({"type": "tent", "radius": 1.6}, 2),
    ({"type": "gaussian"}, 2),
    ({"type": "gaussian", "stddev": 1.0}, 4),
]:
    check(f"border_size of {d}", mi.load_dict(d).border_size(), border)

# tent_table_is_the_left_endpoint_discretisation
for radius in (1.0, 1.5, 3.0):
    f = mi.load_dict({"type": "tent", "radius": radius})
    check(f"tent radius {radius} table = 1 - k/31", table(f), [1 - k / 31 for k in range(31)], 1e-6)

# gaussian_fit_is_the_minimax_approximation (the filter side)
xs = np.arange(401) * 0.005
exact = np.maximum(np.exp(-2 * xs**2) - np.exp(-8.0), 0.0)
check(
    "max |gaussian.eval − (exp(−2x²) − exp(−8))| ≤ 4.2e-4",
    np.max(np.abs([gauss.eval(float(x)) for x in xs] - exact)) <= 4.2e-4,
    True,
)


# half_bright_half_dark_edge_matches_mitsuba
def edge_scene(seed, spp):
    return mi.load_dict(
        {
            "type": "scene",
            "integrator": {"type": "path", "max_depth": 1},
            "sensor": {
                "type": "perspective",
                "fov": 40,
                "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 5], target=[0, 0, 0], up=[0, 1, 0]),
                "film": {"type": "hdrfilm", "width": 8, "height": 2},
                "sampler": {"type": "independent", "sample_count": spp, "seed": seed},
            },
            # Radiance 1 on world x < 0, which the camera sees on the left half of the image.
            "light": {
                "type": "rectangle",
                "to_world": mi.ScalarTransform4f().translate([-50, 0, 0]).scale([50, 50, 1]),
                "emitter": {"type": "area", "radiance": {"type": "rgb", "value": 1.0}},
            },
        }
    )


renders = np.array([np.array(mi.render(edge_scene(seed, 65536)))[:, :, 0] for seed in range(32)])
mean, se = renders.mean(axis=0), renders.std(axis=0, ddof=1) / np.sqrt(len(renders))
print(
    f"edge renders: pixels 3 | 4 = {mean[:, 3].mean():.5f} | {mean[:, 4].mean():.5f} (standard error {se[:, 3:5].max():.1e})"
)
check("edge: left of the edge, both rows", mean[:, 3], [0.8339, 0.8339], 2e-3)
check("edge: right of the edge, both rows", mean[:, 4], [0.1661, 0.1661], 2e-3)
check("edge: outer pixels", [mean[:, 0], mean[:, 7]], [[1.0, 1.0], [0.0, 0.0]], 1e-6)

finish()
