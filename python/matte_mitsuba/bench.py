"""Mitsuba's side of `matte bench`: wall time of `mi.render` for each job and variant
(scene loaded beforehand, best of `--repeats`, after one warm-up render so that llvm_ad_rgb
is timed with its kernel cache warm), and optionally the render time of each of matte's
plugins against the built-in `diffuse` in llvm_ad_rgb's symbolic mode, one process per type
(:mod:`matte_mitsuba.bench_plugin`'s Cornell box, every registered type).

    python -m matte_mitsuba.bench --jobs JOBS.json [--variants scalar_rgb llvm_ad_rgb]
        [--repeats 3] [--plugin-res 256 --plugin-spp 64]

JOBS.json: [{"name": ..., "scene": path, "defines": {name: value}, "spp": N}, ...].
Prints one JSON object on stdout; progress goes to stderr.
"""

import argparse
import json
import sys
from pathlib import Path

import mitsuba as mi

from . import bench_plugin


def time_job(job, repeats):
    scene = mi.load_file(job["scene"], **job.get("defines", {}))
    bench_plugin.timed(scene, job["spp"])  # warm-up: JIT compilation, kernel cache
    return min(bench_plugin.timed(scene, job["spp"]) for _ in range(repeats))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--jobs", required=True)
    ap.add_argument("--variants", nargs="+", default=["scalar_rgb", "llvm_ad_rgb"])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--plugin-res", type=int, default=0, help="0: skip the plugin times")
    ap.add_argument("--plugin-spp", type=int, default=64)
    a = ap.parse_args()
    jobs = json.loads(Path(a.jobs).read_text())
    out = {"renders": [], "plugin": None}
    for variant in a.variants:
        mi.set_variant(variant)
        for job in jobs:
            print(f"mitsuba {variant} {job['name']}", file=sys.stderr, flush=True)
            out["renders"].append({"name": job["name"], "variant": variant, "seconds": time_job(job, a.repeats)})
    if a.plugin_res > 0:
        print("mitsuba llvm_ad_rgb plugins, one process per type", file=sys.stderr, flush=True)
        rounds = bench_plugin.time_all("llvm_ad_rgb", a.plugin_res, a.plugin_spp, a.repeats)
        seconds = {kind: min(times) for kind, times in rounds.items()}
        out["plugin"] = {"variant": "llvm_ad_rgb", "res": a.plugin_res, "spp": a.plugin_spp, "seconds": seconds}
    print(json.dumps(out))


if __name__ == "__main__":
    main()
