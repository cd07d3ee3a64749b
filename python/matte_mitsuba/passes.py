"""Mitsuba side of `matte validate`: renders a scene K times with independent seeds in one
variant (matte's plugins loaded) and writes each pass image. It only renders: the spp per
pass comes from the Rust harness, and every statistic (moments, region means, tests) is
computed in Rust (`rust/matte/src/validate/passes.rs`), once for both renderers.

    python -m matte_mitsuba.passes SCENE.xml --out DIR --spp N
        [--variant scalar_rgb] [--passes K] [--seed S] [-D name=value ...]

Writes DIR/pass_0000.exr ... (RGB float32; pass k uses seed S + k) and DIR/passes.json
(timings, Mitsuba's version). Prints "pass k/K" lines as it goes (the harness turns them into a progress bar).
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
    ap.add_argument("--spp", type=int, required=True, help="samples per pixel per pass")
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("-D", dest="defines", action="append", default=[])
    a = ap.parse_args()

    import mitsuba as mi

    mi.set_variant(a.variant)
    params = {}
    for d in a.defines:
        k, _, v = d.partition("=")
        params[k] = v
    t0 = time.perf_counter()
    scene = mi.load_file(a.scene, **params)
    load_seconds = time.perf_counter() - t0
    os.makedirs(a.out, exist_ok=True)
    seconds = 0.0
    for k in range(a.passes):
        t0 = time.perf_counter()
        img = np.array(mi.render(scene, spp=a.spp, seed=a.seed + k), dtype=np.float32)[..., :3]
        seconds += time.perf_counter() - t0
        mi.Bitmap(np.ascontiguousarray(img)).write(os.path.join(a.out, f"pass_{k:04d}.exr"))
        print(f"pass {k + 1}/{a.passes}", flush=True)
    with open(os.path.join(a.out, "passes.json"), "w") as f:
        json.dump(
            {
                "mitsuba": mi.__version__,
                "variant": a.variant,
                "passes": a.passes,
                "spp": a.spp,
                "seed": a.seed,
                "load_seconds": load_seconds,
                "render_seconds": seconds,
            },
            f,
        )


if __name__ == "__main__":
    try:
        main()
    except Exception as e:  # one line for the harness, not a traceback
        print(f"mitsuba: {type(e).__name__}: {e}".splitlines()[0], file=sys.stderr)
        sys.exit(1)
