#!/usr/bin/env python3
"""Writes tests/render/samplers/mitsuba_reference.json from live Mitsuba 3.9.1 (scalar_rgb), the
oracle of tests/render/samplers.rs. Run by hand with the venv's Python:

    .venv/bin/python tests/render/samplers/generate_reference.py tests/render/samplers/mitsuba_reference.json

* "samplers": for each sampler plugin and properties, the rounded sample_count and, after
  `sampler.seed(seed)`, every sample's dimensions next_1d, next_2d, next_1d, next_2d, next_1d,
  next_2d (then `advance()`).
* "thinlens": rays of a `thinlens` sensor for film and aperture samples.
"""

import json
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)

SAMPLER_CASES = [
    ("stratified", {"jitter": False}, 9, 0, 5),
    ("stratified", {}, 10, 3, 77),
    ("multijitter", {"jitter": False}, 12, 0, 5),
    ("multijitter", {}, 10, 1, 1234),
    ("orthogonal", {"jitter": False}, 9, 0, 5),
    ("orthogonal", {}, 25, 2, 99),
    ("orthogonal", {"jitter": False, "strength": 3}, 9, 0, 8),
    ("orthogonal", {"strength": 3}, 4, 1, 8),
    ("ldsampler", {}, 16, 0, 5),
    ("ldsampler", {}, 64, 7, 4242),
    ("independent", {}, 4, 2, 5),
]

# (requested sample_count, plugin) -> Mitsuba's rounded sample_count.
ROUNDING = [
    (t, n)
    for t in ("stratified", "multijitter", "orthogonal", "ldsampler", "independent")
    for n in (1, 2, 3, 5, 8, 10, 17, 50, 100, 1000)
]


def samplers():
    out = []
    for t, props, n, base, seed in SAMPLER_CASES:
        d = {"type": t, "sample_count": n, "seed": base}
        d.update(props)
        s = mi.load_dict(d)
        s.seed(seed)
        vals = []
        for _ in range(s.sample_count()):
            row = []
            for k in range(6):
                if k % 2 == 0:
                    row.append(float(s.next_1d()))
                else:
                    p = s.next_2d()
                    row += [float(p[0]), float(p[1])]
            vals.append(row)
            s.advance()
        out.append(
            {"type": t, "props": props, "n": n, "base": base, "seed": seed, "count": s.sample_count(), "vals": vals}
        )
    return out


def rounding():
    return [
        {"type": t, "n": n, "count": mi.load_dict({"type": t, "sample_count": n}).sample_count()} for t, n in ROUNDING
    ]


THINLENS = {
    "type": "thinlens",
    "fov": 35.0,
    "fov_axis": "smaller",
    "aperture_radius": 0.3,
    "focus_distance": 4.5,
    "near_clip": 0.05,
    "far_clip": 80.0,
    "to_world": mi.ScalarTransform4f().look_at(origin=[1, 2, 6], target=[0, 0.5, 0], up=[0, 1, 0]),
    "film": {"type": "hdrfilm", "width": 40, "height": 30},
}


def thinlens():
    cam = mi.load_dict(THINLENS)
    rays = []
    for _i, (fx, fy, ax, ay) in enumerate(
        [
            (0.5, 0.5, 0.5, 0.5),
            (0.1, 0.9, 0.2, 0.7),
            (0.95, 0.05, 0.99, 0.01),
            (0.3, 0.6, 0.0, 0.0),
            (0.7, 0.2, 0.6, 0.95),
        ]
    ):
        ray, w = cam.sample_ray(0.0, 0.5, mi.Point2f(fx, fy), mi.Point2f(ax, ay))
        rays.append(
            {
                "film": [fx, fy],
                "aperture": [ax, ay],
                "o": list(map(float, ray.o)),
                "d": list(map(float, ray.d)),
                "maxt": float(ray.maxt),
                "weight": float(w[0]),
            }
        )
    props = {k: v for k, v in THINLENS.items() if k not in ("to_world", "film", "type")}
    return {"props": props, "origin": [1, 2, 6], "target": [0, 0.5, 0], "up": [0, 1, 0], "film": [40, 30], "rays": rays}


def main():
    data = {"mitsuba": mi.__version__, "samplers": samplers(), "rounding": rounding(), "thinlens": thinlens()}
    with open(sys.argv[1], "w") as f:
        json.dump(data, f, indent=None, separators=(",", ":"))
        f.write("\n")


if __name__ == "__main__":
    main()
