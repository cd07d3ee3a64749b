"""Render time of matte's plugins against Mitsuba's built-in `diffuse`, measured in one run on
this machine: Cornell box (mi.cornell_box(), 256x256, 64 spp), all three materials replaced by
the plugin under test, in llvm_ad_rgb with Dr.Jit's default (symbolic) mode. Each type runs in
its own process (a symbolic call traces every BSDF type loaded in the process), and each time
is the best of `--repeats` after a warm-up render (JIT compilation, table building).

    .venv/bin/python validation/bench_plugin.py [--variant llvm_ad_rgb] [--repeats 3]
    .venv/bin/python validation/bench_plugin.py --one wolff      # one type: JSON on stdout
"""
import argparse
import json
import subprocess
import sys
import time

from matte_mitsuba import BSDF_TYPES as TYPES  # the plugin names, as the build wrote them


def scene(mi, kind, res):
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = res
    for name in ("white", "red", "green"):
        d[name]["type"] = kind
    return mi.load_dict(d)


def timed(s, spp):
    import drjit as dr
    import mitsuba as mi
    t = time.perf_counter()
    img = mi.render(s, spp=spp, seed=0)
    dr.eval(img)
    dr.sync_thread()
    return time.perf_counter() - t


def best_time(kind, variant, res, spp, repeats):
    """Best-of time of one type in this process (after a warm-up render)."""
    import mitsuba as mi
    mi.set_variant(variant)
    import matte_mitsuba  # noqa: F401  (registers the plugins)
    s = scene(mi, kind, res)
    timed(s, spp)
    return min(timed(s, spp) for _ in range(repeats))


def time_in_subprocess(kind, variant, res, spp, repeats):
    out = subprocess.run([sys.executable, __file__, "--one", kind, "--variant", variant, "--res", str(res),
                          "--spp", str(spp), "--repeats", str(repeats)], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)["seconds"]


def time_all(variant, res, spp, repeats, types=TYPES):
    """{type: best seconds} for `diffuse` and every type, each in its own process."""
    return {k: time_in_subprocess(k, variant, res, spp, repeats) for k in ["diffuse"] + list(types)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--res", type=int, default=256)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--types", nargs="+", default=TYPES, choices=TYPES)
    ap.add_argument("--one", help="time this one type (or diffuse) in this process; print JSON")
    a = ap.parse_args()
    if a.one:
        print(json.dumps({"type": a.one, "seconds": best_time(a.one, a.variant, a.res, a.spp, a.repeats)}))
        return
    print(f"Cornell box {a.res}x{a.res}, {a.spp} spp, {a.variant}, best of {a.repeats}, one process per type")
    best = time_all(a.variant, a.res, a.spp, a.repeats, a.types)
    print(f"  diffuse     {best['diffuse']:.3f} s")
    for k in a.types:
        print(f"  {k:<11} {best[k]:.3f} s  {best[k] / best['diffuse']:.3f}x diffuse")


if __name__ == "__main__":
    main()
