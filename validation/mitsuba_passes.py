"""Mitsuba side of `matte validate`: renders a scene K times with independent seeds in one
variant (matte's plugins loaded) and writes the per-pixel mean and sample variance of the K
pass images, plus the per-pass image means, for the Rust harness to compare.

    .venv/bin/python validation/mitsuba_passes.py SCENE.xml --out DIR [--variant scalar_rgb]
        [--spp N] [--passes K] [--seed S] [-D name=value ...]

Writes DIR/mean.exr, DIR/var.exr (RGB float32) and DIR/passes.json. Prints "pass k/K" lines
as it goes (the harness turns them into a progress bar).
"""
import argparse
import json
import os
import sys
import time

import numpy as np


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("--out", required=True)
    ap.add_argument("--variant", default="scalar_rgb")
    ap.add_argument("--spp", type=int, default=None, help="samples per pixel per pass (default: the scene's)")
    ap.add_argument("--scene-multiple", type=int, default=None,
                    help="instead of --spp: this many times the scene's sample_count in total, split over the passes")
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("-D", dest="defines", action="append", default=[])
    ap.add_argument("--region", action="append", default=[],
                    help="x0,y0,x1,y1 as fractions of the image: its mean is recorded per pass")
    a = ap.parse_args()

    import mitsuba as mi
    mi.set_variant(a.variant)
    import matte_mitsuba  # noqa: F401  (registers the plugins)
    params = {}
    for d in a.defines:
        k, _, v = d.partition("=")
        params[k] = v
    t0 = time.perf_counter()
    scene = mi.load_file(a.scene, **params)
    load_seconds = time.perf_counter() - t0
    scene_spp = scene.sensors()[0].sampler().sample_count()
    if a.spp:
        spp = a.spp
    elif a.scene_multiple:
        spp = max(a.scene_multiple * scene_spp // a.passes, 1)  # as validate::passes::Budget
    else:
        spp = scene_spp
    total = mean = m2 = None
    pass_means = []
    regions = [[float(v) for v in r.split(",")] for r in a.region]
    region_pass_means = [[] for _ in regions]
    t0 = time.perf_counter()
    for k in range(a.passes):
        img = np.array(mi.render(scene, spp=spp, seed=a.seed + k), dtype=np.float64)[..., :3]
        pass_means.append(img.mean(axis=(0, 1)).tolist())
        h, w = img.shape[:2]
        for acc, (x0, y0, x1, y1) in zip(region_pass_means, regions):
            # Same pixel rounding as the Rust side (validate::passes::region_mean).
            c0, r0 = min(int(x0 * w), w - 1), min(int(y0 * h), h - 1)
            c1 = min(max(int(np.ceil(x1 * w)), c0 + 1), w)
            r1 = min(max(int(np.ceil(y1 * h)), r0 + 1), h)
            acc.append(img[r0:r1, c0:c1].mean(axis=(0, 1)).tolist())
        if mean is None:
            mean, m2 = np.zeros_like(img), np.zeros_like(img)
        d = img - mean
        mean += d / (k + 1)
        m2 += d * (img - mean)
        print(f"pass {k + 1}/{a.passes}", flush=True)
    seconds = time.perf_counter() - t0
    var = m2 / max(a.passes - 1, 1)
    os.makedirs(a.out, exist_ok=True)
    mi.Bitmap(mean.astype(np.float32)).write(os.path.join(a.out, "mean.exr"))
    mi.Bitmap(var.astype(np.float32)).write(os.path.join(a.out, "var.exr"))
    with open(os.path.join(a.out, "passes.json"), "w") as f:
        json.dump({"variant": a.variant, "passes": a.passes, "spp": spp, "seed": a.seed,
                   "pass_means": pass_means, "region_pass_means": region_pass_means, "load_seconds": load_seconds, "render_seconds": seconds}, f)


if __name__ == "__main__":
    try:
        main()
    except Exception as e:  # one line for the harness, not a traceback
        print(f"mitsuba: {type(e).__name__}: {e}".splitlines()[0], file=sys.stderr)
        sys.exit(1)
