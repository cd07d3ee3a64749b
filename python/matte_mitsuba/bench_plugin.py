"""Render time of matte's plugins against Mitsuba's built-in `diffuse`, measured in one run on
this machine: Cornell box (mi.cornell_box(), 256x256, 64 spp), all three materials replaced by
the plugin under test, in llvm_ad_rgb with Dr.Jit's default (symbolic) mode. Every registered
type is timed, `tabulated_brdf` on the packaged V-cavity table (σ = 0.3). Each type runs in its
own process (a symbolic call traces every BSDF type loaded in the process), and each time is
the best of `--repeats` after a warm-up render (JIT compilation, table building).

    python -m matte_mitsuba.bench_plugin [--variant llvm_ad_rgb] [--repeats 3] [--rounds 1] [--lanes 8]
    python -m matte_mitsuba.bench_plugin --one wolff      # one type: JSON on stdout
    python -m matte_mitsuba.bench_plugin --one wolff --bitmap   # its int_ior as a bitmap
    python -m matte_mitsuba.bench_plugin --float-fast-path OLD [--rounds 2]

``--bitmap`` gives each type's numeric parameter (``SHAPE_PARAMETER``) as a 16×16 bitmap
texture holding the default value everywhere, so the image is the float's and only the
textured code path differs. ``--plugin-root DIR`` runs the timed processes with the
``matte_mitsuba`` in DIR (a folder holding a ``matte_mitsuba`` package, e.g. another
revision's ``python`` folder after its ``cpp/build_plugin.py``) first on ``PYTHONPATH``;
``--one`` prints the folder it loaded. ``--float-fast-path OLD`` times, per type, the float
parameter with the plugin build in OLD (a revision before textured parameters) and with this
one, and the bitmap with this one; every configuration in its own process, `--rounds` rounds
interleaved (machine load drifts), best over all, as wall time and as the process's CPU time
(less sensitive to other work on a shared machine). Without it, `--rounds` rounds of every
type are interleaved the same way and each type's ratio to `diffuse` is given per round.
``--lanes 8`` runs Dr.Jit's LLVM backend at 8 lanes (AVX2's width, target CPU `haswell`) on a
machine whose own width is 16 (AVX-512), so that one machine measures both CPU classes' lane
widths. ``--lanes 16`` on an 8-wide (AVX2) machine runs Dr.Jit's 16-lane kernels as pairs of
8-wide instructions: the code an AVX-512 machine runs, not its timing (measure that on one).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import matte_mitsuba
from matte_mitsuba import BSDF_TYPES as TYPES  # the plugin names, as the build wrote them
from matte_mitsuba import registry

# Each type's first numeric parameter and its default, from the model registry.
SHAPE_PARAMETER = {
    m["name"]: (p[0]["name"], registry.default(p[0]))
    for m in registry.MODELS
    for p in [registry.numeric_parameters(m)]
    if p
}


def required(kind):
    """Properties a type needs beyond its defaults: each file parameter (the table
    `tabulated_brdf` reads) given the packaged V-cavity table; none for Mitsuba's own types
    (`diffuse`, the reference)."""
    if kind not in registry.NAMES:
        return {}
    table = matte_mitsuba.ground_truth_path("v_cavities_sigma0.3")
    return {p["name"]: table for p in registry.file_parameters(kind)}


def constant_bitmap(mi, value, folder):
    """A 16×16 one-channel EXR holding `value`: the texture form of a number."""
    import numpy as np

    path = os.path.join(folder, f"constant_{value}.exr")
    mi.Bitmap(np.full((16, 16, 1), value, dtype=np.float32)).write(path)
    return {"type": "bitmap", "filename": path, "raw": True}


def scene(mi, kind, res, bitmap_folder=None):
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = res
    for name in ("white", "red", "green"):
        d[name]["type"] = kind
        d[name].update(required(kind))
        if bitmap_folder is not None:
            param, value = SHAPE_PARAMETER[kind]
            d[name][param] = constant_bitmap(mi, value, bitmap_folder)
    return mi.load_dict(d)


def timed_wall_cpu(s, spp):
    """Wall time and CPU time (all threads of this process: user + system) of one render. On a
    machine shared with other work the CPU time depends much less on the load than the wall
    time does."""
    import drjit as dr
    import mitsuba as mi

    c0, t = time.process_time(), time.perf_counter()
    img = mi.render(s, spp=spp, seed=0)
    dr.eval(img)
    dr.sync_thread()
    return time.perf_counter() - t, time.process_time() - c0


def timed(s, spp):
    return timed_wall_cpu(s, spp)[0]


def set_llvm_lanes(lanes=None):
    """Dr.Jit's LLVM backend at `lanes` lanes from now on (before any kernel is compiled): the
    CPU's own width keeps its target, 8 targets `haswell` (AVX2, FMA) without AVX-512. Dr.Jit
    has no Python binding for this, so libdrjit-core's `jit_llvm_set_target` is called
    directly. Returns the width Dr.Jit then reports (without `lanes`, only that)."""
    import ctypes

    import drjit as dr

    name = {"darwin": "libdrjit-core.dylib", "win32": "drjit-core.dll"}.get(sys.platform, "libdrjit-core.so")
    lib = ctypes.CDLL(os.path.join(os.path.dirname(dr.__file__), name))
    try:
        set_target = lib._Z19jit_llvm_set_targetPKcS0_j
        features, width = lib._Z24jit_llvm_target_featuresv, lib._Z21jit_llvm_vector_widthv
        cpu = lib._Z19jit_llvm_target_cpuv
    except AttributeError:
        raise SystemExit(f"--lanes: Dr.Jit {dr.__version__} has no jit_llvm_set_target") from None
    set_target.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_uint32]
    features.restype, width.restype, cpu.restype = ctypes.c_char_p, ctypes.c_uint32, ctypes.c_char_p
    if lanes and lanes != width():
        if lanes == 8:
            kept = ",".join(f for f in features().decode().split(",") if "avx512" not in f)
            set_target(b"haswell", kept.encode(), 8)
        else:
            # 16 lanes on an 8-wide CPU: Dr.Jit's 16-lane code, which LLVM runs as pairs of
            # 8-wide instructions (the shape of AVX-512's kernels, not its timing).
            set_target(cpu(), features(), lanes)
    return width()


def best_time(kind, variant, res, spp, repeats, bitmap=False, lanes=None):
    """Best-of wall and CPU times of one type in this process (after a warm-up render)."""
    import mitsuba as mi

    mi.set_variant(variant)
    if lanes:
        set_llvm_lanes(lanes)
    import matte_mitsuba  # noqa: F401  (registers the plugins)

    with tempfile.TemporaryDirectory() as folder:
        s = scene(mi, kind, res, folder if bitmap else None)
        timed(s, spp)
        times = [timed_wall_cpu(s, spp) for _ in range(repeats)]
        return min(t[0] for t in times), min(t[1] for t in times)


def time_in_subprocess(kind, variant, res, spp, repeats, bitmap=False, plugin_root=None, both=False, lanes=None):
    """Best wall seconds of one configuration in its own process; (wall, CPU) with `both`."""
    env = dict(os.environ)
    if plugin_root:
        env["PYTHONPATH"] = os.pathsep.join([os.path.abspath(plugin_root)] + [p for p in [env.get("PYTHONPATH")] if p])
    # This file run as a script (absolute imports only), so that `--plugin-root`'s matte_mitsuba,
    # first on PYTHONPATH, is the one it imports even when that build has no bench_plugin.
    out = subprocess.run(
        [
            sys.executable,
            os.path.abspath(__file__),
            "--one",
            kind,
            "--variant",
            variant,
            "--res",
            str(res),
            "--spp",
            str(spp),
            "--repeats",
            str(repeats),
        ]
        + (["--bitmap"] if bitmap else [])
        + (["--lanes", str(lanes)] if lanes else []),
        capture_output=True,
        text=True,
        check=True,
        env=env,
    )
    result = json.loads(out.stdout)
    if plugin_root and not result["plugins"].startswith(os.path.abspath(plugin_root)):
        raise RuntimeError(f"--plugin-root {plugin_root}: the child loaded {result['plugins']}")
    return (result["seconds"], result["cpu_seconds"]) if both else result["seconds"]


def time_all(variant, res, spp, repeats, types=TYPES, plugin_root=None, rounds=1, lanes=None):
    """{type: [best seconds of each round]} for `diffuse` and every type, each in its own
    process, the types taking turns round by round."""
    times = {}
    for _ in range(rounds):
        for k in ["diffuse"] + list(types):
            t = time_in_subprocess(k, variant, res, spp, repeats, plugin_root=plugin_root, lanes=lanes)
            times.setdefault(k, []).append(t)
    return times


def float_fast_path(old_root, variant, res, spp, repeats, rounds, types):
    """Per type: float parameters with the `old_root` build and with this one, and a bitmap
    parameter with this one; {configuration: best seconds over `rounds` interleaved rounds}."""
    configs = [("diffuse", "this", False)]
    for k in types:
        configs += [(k, "old", False), (k, "this", False)]
        if k in SHAPE_PARAMETER:
            configs.append((k, "this", True))
    best = {"wall": {}, "cpu": {}}
    for r in range(rounds):
        for kind, build, bitmap in configs:
            key = f"{kind} {build} {'bitmap' if bitmap else 'float'}"
            wall, cpu = time_in_subprocess(
                kind, variant, res, spp, repeats, bitmap, old_root if build == "old" else None, both=True
            )
            best["wall"][key] = min(best["wall"].get(key, wall), wall)
            best["cpu"][key] = min(best["cpu"].get(key, cpu), cpu)
            print(
                f"  round {r + 1}/{rounds}: {key:<26} wall {wall:.3f} s, CPU {cpu:.3f} s", file=sys.stderr, flush=True
            )
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--res", type=int, default=256)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--types", nargs="+", default=TYPES, choices=TYPES)
    ap.add_argument("--one", help="time this one type (or diffuse) in this process; print JSON")
    ap.add_argument("--bitmap", action="store_true", help="with --one: the numeric parameter as a constant bitmap")
    ap.add_argument("--plugin-root", metavar="DIR", help="the timed processes import matte_mitsuba from DIR")
    ap.add_argument(
        "--float-fast-path",
        metavar="OLD_ROOT",
        help="compare float parameters with the build in OLD_ROOT (the folder holding its matte_mitsuba)",
    )
    ap.add_argument("--rounds", type=int, help="interleaved rounds (default 1; 2 with --float-fast-path)")
    ap.add_argument("--lanes", type=int, choices=[8, 16], help="Dr.Jit's LLVM vector width (default: the CPU's)")
    ap.add_argument("--json", metavar="FILE", help="with --float-fast-path: write the times here")
    a = ap.parse_args()
    if a.one and a.plugin_root:
        # --one times in this process, whose matte_mitsuba is already imported.
        ap.error(f"--plugin-root applies to the timed processes, not to --one; run PYTHONPATH={a.plugin_root} instead")
    if a.one:
        if a.bitmap and a.one not in SHAPE_PARAMETER:
            ap.error(f"--bitmap: {a.one} has no numeric parameter")
        wall, cpu = best_time(a.one, a.variant, a.res, a.spp, a.repeats, a.bitmap, a.lanes)
        print(
            json.dumps(
                {
                    "type": a.one,
                    "bitmap": a.bitmap,
                    "plugins": matte_mitsuba.PLUGIN_ROOT,
                    "lanes": set_llvm_lanes() if a.variant.startswith("llvm") else None,
                    "seconds": wall,
                    "cpu_seconds": cpu,
                }
            )
        )
        return
    if a.float_fast_path:
        print(
            f"Cornell box {a.res}x{a.res}, {a.spp} spp, {a.variant}, best of {a.repeats} per process, "
            f"{a.rounds} rounds, one process per configuration; old build: {a.float_fast_path}"
        )
        times = float_fast_path(a.float_fast_path, a.variant, a.res, a.spp, a.repeats, a.rounds or 2, a.types)
        for clock, best in times.items():
            print(f"{clock} time (s): diffuse {best['diffuse this float']:.3f}")
            print(f"  {'type':<13} {'old float':>9} {'float':>9} {'float/old':>9} {'bitmap':>9} {'bitmap/float':>12}")
            for k in a.types:
                old, new = best[f"{k} old float"], best[f"{k} this float"]
                bm = best.get(f"{k} this bitmap")
                tail = f" {bm:9.3f} {bm / new:12.3f}" if bm else ""
                print(f"  {k:<13} {old:9.3f} {new:9.3f} {new / old:9.3f}{tail}")
        if a.json:
            with open(a.json, "w") as f:
                json.dump(
                    {
                        "res": a.res,
                        "spp": a.spp,
                        "variant": a.variant,
                        "repeats": a.repeats,
                        "rounds": a.rounds or 2,
                        "old_root": os.path.abspath(a.float_fast_path),
                        "seconds": times,
                    },
                    f,
                    indent=1,
                )
        return
    rounds = a.rounds or 1
    lanes = f", {a.lanes} lanes" if a.lanes else ""
    print(
        f"Cornell box {a.res}x{a.res}, {a.spp} spp, {a.variant}{lanes}, best of {a.repeats}, "
        f"one process per type, {rounds} round(s)"
    )
    times = time_all(a.variant, a.res, a.spp, a.repeats, a.types, a.plugin_root, rounds, a.lanes)
    diffuse = times["diffuse"]
    print(f"  diffuse        {min(diffuse):.3f} s")
    for k in a.types:
        ratios = [t / d for t, d in zip(times[k], diffuse)]
        per_round = " ".join(f"{r:.3f}" for r in ratios)
        rounds_text = f" (mean of the rounds {sum(ratios) / len(ratios):.3f}x: {per_round})" if rounds > 1 else ""
        print(f"  {k:<14} {min(times[k]):.3f} s  {min(times[k]) / min(diffuse):.3f}x diffuse{rounds_text}")


if __name__ == "__main__":
    main()
