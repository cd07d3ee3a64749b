"""Render-time overhead of matte's plugins against Mitsuba's built-in `diffuse`, measured in
one run on this machine: Cornell box (mi.cornell_box(), 256x256, 64 spp), all three
materials replaced by the plugin under test. Runs alternate between plugins; each time is
the best of `--repeats` after a warm-up render (JIT compilation, table building).

    .venv/bin/python validation/bench_plugin.py [--variants scalar_rgb llvm_ad_rgb] [--repeats 3]

llvm_ad_rgb runs in evaluated mode (what matte's plugins need) for both `diffuse` and the
plugins, so the ratio isolates the plugin; the symbolic-mode `diffuse` time is printed too.
"""
import argparse
import time

import drjit as dr
import mitsuba as mi

TYPES = ["lambert", "oren_nayar", "eon", "wolff", "ginneken"]


def scene(kind, res):
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = res
    for name in ("white", "red", "green"):
        d[name]["type"] = kind
    return mi.load_dict(d)


def timed(s, spp):
    t = time.perf_counter()
    img = mi.render(s, spp=spp, seed=0)
    dr.eval(img)
    dr.sync_thread()
    return time.perf_counter() - t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--variants", nargs="+", default=["scalar_rgb", "llvm_ad_rgb"])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--res", type=int, default=256)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--types", nargs="+", default=TYPES, choices=TYPES)
    a = ap.parse_args()
    print(f"Cornell box {a.res}x{a.res}, {a.spp} spp, best of {a.repeats}")
    for variant in a.variants:
        mi.set_variant(variant)
        import matte_mitsuba
        matte_mitsuba.register()
        if variant.startswith("llvm"):
            dr.set_flag(dr.JitFlag.SymbolicLoops, True)
            dr.set_flag(dr.JitFlag.SymbolicCalls, True)
            s = scene("diffuse", a.res)
            timed(s, a.spp)
            symbolic = min(timed(s, a.spp) for _ in range(a.repeats))
            matte_mitsuba.evaluated_mode()
        scenes = {k: scene(k, a.res) for k in ["diffuse"] + a.types}
        for s in scenes.values():
            timed(s, a.spp)  # warm-up
        best = {k: float("inf") for k in scenes}
        for _ in range(a.repeats):
            for k, s in scenes.items():
                best[k] = min(best[k], timed(s, a.spp))
        mode = " (evaluated mode)" if variant.startswith("llvm") else ""
        print(f"\n{variant}{mode}: diffuse {best['diffuse']:.3f} s")
        for k in a.types:
            print(f"  {k:<11} {best[k]:.3f} s  {100 * (best[k] / best['diffuse'] - 1):+6.1f} % vs diffuse")
        if variant.startswith("llvm"):
            print(f"  (diffuse in symbolic mode: {symbolic:.3f} s)")


if __name__ == "__main__":
    main()
