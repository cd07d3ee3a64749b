"""Speed of `matte render` beside Mitsuba 3.9.1 on the same scene, measured in one run on this
machine: wall time of the render (scene already loaded, best of `--repeats`), samples/s, and
rays/s. matte counts its rays; Mitsuba does not report them, so its rays/s is estimated with
matte's rays per sample (both trace the same expected paths), and marked as such.

    .venv/bin/python validation/bench_renderer.py [--scene mitsuba_scenes/cornell_box.xml]
        [--res 256] [--spp 64] [--repeats 3] [--variants scalar_rgb llvm_ad_rgb]

llvm_ad_rgb is timed in its default symbolic mode after a warm-up render (kernel cache warm).
"""
import argparse
import json
import subprocess
import time
from pathlib import Path

import drjit as dr
import mitsuba as mi

ROOT = Path(__file__).resolve().parent.parent


def matte_render(scene, res, spp, out):
    cmd = [str(ROOT / "target/release/matte"), "render", str(scene), "-D", f"res={res}", "--spp", str(spp),
           "-o", str(out), "--quiet"]
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def mitsuba_time(variant, scene, res, spp, repeats):
    mi.set_variant(variant)
    import matte_mitsuba  # noqa: F401  (plugins, in case the scene uses them)
    s = mi.load_file(str(scene), res=res)
    def once():
        t = time.perf_counter()
        img = mi.render(s, spp=spp, seed=0)
        dr.eval(img)
        dr.sync_thread()
        return time.perf_counter() - t
    once()  # warm-up: JIT compilation / kernel cache
    return min(once() for _ in range(repeats))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default=str(ROOT / "mitsuba_scenes/cornell_box.xml"))
    ap.add_argument("--res", type=int, default=256)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--variants", nargs="+", default=["scalar_rgb", "llvm_ad_rgb"])
    a = ap.parse_args()
    out = Path("/tmp/bench_renderer.exr")
    matte_render(a.scene, a.res, a.spp, out)  # warm-up (page cache)
    runs = [matte_render(a.scene, a.res, a.spp, out) for _ in range(a.repeats)]
    best = min(runs, key=lambda r: r["render_seconds"])
    samples = best["samples"]
    rays_per_sample = best["rays"] / samples
    rows = [("matte", best["render_seconds"], best["rays_per_second"], "counted")]
    for v in a.variants:
        t = mitsuba_time(v, a.scene, a.res, a.spp, a.repeats)
        rows.append((f"mitsuba {v}", t, samples * rays_per_sample / t, "estimated"))
    print(f"{Path(a.scene).name} {a.res}x{a.res}, {a.spp} spp, {best['threads']} threads, best of {a.repeats}")
    print(f"{'renderer':<24}{'seconds':>10}{'Msamples/s':>12}{'Mrays/s':>10}  rays   time / matte")
    for name, t, rps, how in rows:
        print(f"{name:<24}{t:>10.3f}{samples / t / 1e6:>12.3f}{rps / 1e6:>10.2f}  {how:<9}{t / rows[0][1]:>6.2f}x")
    print(json.dumps({"scene": a.scene, "res": a.res, "spp": a.spp, "rows": [
        {"renderer": n, "seconds": t, "samples_per_second": samples / t, "rays_per_second": r, "rays": h}
        for n, t, r, h in rows]}))


if __name__ == "__main__":
    main()
