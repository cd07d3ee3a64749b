"""The plugin on an NVIDIA GPU, in one command (docs/testing.md, "GPU check"). In the Python
environment where the matte-mitsuba wheel is installed:

    python -m matte_mitsuba.gpu_check          # exit 0: all agree; 1: a mismatch; 0 without a GPU

Three checks of the `cuda_ad_rgb` variant in Dr.Jit's default (symbolic) mode, each in its
own process (a symbolic call traces every BSDF type loaded in the process):

1. **Image mean.** The bundled `all_types.xml` (every matte type) rendered with `--seeds`
   seeds in `cuda_ad_rgb` and in `llvm_ad_rgb`: per channel, the two means must agree within
   4.5 standard errors (from the spread over seeds), i.e. the same expectation.
2. **Gradients.** For one parameter per type, d(image mean)/d(parameter) by `prb` on the
   Cornell box against central finite differences of renders with the same seed, within 1 %
   (as `tests/plugin/test_gradients.py` does in `llvm_ad_rgb`).
3. **Speed.** Each type's render time on the Cornell box (256², 64 spp, best of 3 after a
   warm-up; `python -m matte_mitsuba.bench_plugin --one`) against Mitsuba's own `diffuse`: reported,
   not judged.

Prints one table. Without a GPU (no `cuda_ad_rgb` variant, or no CUDA driver) it says so and
exits 0. `--device-variant llvm_ad_rgb` runs the same checks on the CPU (a dry run of the
script itself).
"""

import argparse
import json
import os
import subprocess
import sys
import time

from . import SCENES, bench_plugin, registry
from .gradient_check import adjoint_gradient, central_difference

SCENE = os.path.join(SCENES, "all_types.xml")

# One differentiable parameter per type, its value and finite-difference step: the first
# numeric parameter of every registered model (reflectance for a model without one) at its
# default, except where a value away from the default or a smaller step is checked.
GRADIENT_OVERRIDES = {
    "oren_nayar": ({"sigma": 0.5}, 1e-2),
    "eon": ({"roughness": 0.5}, 1e-2),
    "wolff": ({"int_ior": 1.5}, 1e-2),
    "ginneken": ({"roughness": 0.4}, 4e-3),
    "roughdiffuse": ({"alpha": 0.4}, 1e-2),
}


def gradient_cases(models):
    cases = []
    for m in models:
        numeric = registry.numeric_parameters(m)
        if not numeric:
            # The properties a type needs beyond its defaults (tabulated_brdf's table).
            required = bench_plugin.required(m)
            cases.append((m["name"], required, "reflectance.value", 1e-2))
            continue
        fixed, h = GRADIENT_OVERRIDES.get(m["name"], ({}, 1e-2))
        if m.get("sampler", "cosine") != "cosine":
            # Same-seed finite differences would move the sampled directions with the
            # parameter: the adjoint is their derivative only under a fixed sampler
            # (docs/sampling.md#gradients).
            fixed = {**fixed, "sampling": "cosine"}
        cases.append((m["name"], fixed, numeric[0]["name"], h))
    return cases


GRADIENT_CASES = gradient_cases(registry.MODELS)
GRADIENT_TOLERANCE = 0.01
MEAN_Z_LIMIT = 4.5


def child(args):
    """Runs one measurement in this process and prints its JSON."""
    import mitsuba as mi
    import numpy as np

    mi.set_variant(args.variant)
    if args.child == "probe":
        print(json.dumps({"ok": True}))
        return
    if args.child == "mean":
        scene = mi.load_file(SCENE, res=args.res, spp=args.spp)
        means = []
        for seed in range(args.seeds):
            img = np.array(mi.render(scene, seed=seed), dtype=np.float64)
            means.append(img[..., :3].reshape(-1, 3).mean(axis=0).tolist())
        print(json.dumps({"means": means}))
        return
    if args.child == "gradient":
        kind, fixed, name, h = next(c for c in GRADIENT_CASES if c[0] == args.kind)
        d = mi.cornell_box()
        d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = 24
        d["integrator"] = {"type": "prb", "max_depth": 4, "rr_depth": 1000}
        for obj in ("white", "red", "green"):
            d[obj]["type"] = kind
            d[obj].update(fixed)
        scene = mi.load_dict(d)
        params = mi.traverse(scene)
        key = "white." + name
        base = np.array(params[key]).ravel().copy()
        spp, seed = 8, 3

        def value(delta):
            if name.endswith("value"):
                return mi.Color3f(*[float(x) + delta for x in base])
            return mi.Float(float(base[0]) + delta)

        params[key] = value(0.0)
        ad = float(np.sum(adjoint_gradient(mi, scene, params, key, spp, seed)))
        fd = central_difference(mi, scene, params, key, value, h, spp, seed)
        print(json.dumps({"ad": ad, "fd": fd}))
        return
    raise SystemExit(f"unknown child {args.child}")


def run_child(variant, what, **extra):
    cmd = [sys.executable, "-m", "matte_mitsuba.gpu_check", "--child", what, "--variant", variant]
    for k, v in extra.items():
        cmd += [f"--{k}", str(v)]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        last = (out.stderr.strip().splitlines() or ["(no output)"])[-1]
        return None, last
    return json.loads(out.stdout.strip().splitlines()[-1]), None


def mean_check(device, reference, a):
    rows, ok = [], True
    got = {}
    for v in (device, reference):
        t = time.perf_counter()
        r, err = run_child(v, "mean", res=a.res, spp=a.spp, seeds=a.seeds)
        if r is None:
            return [("image mean", v, "error", err)], False
        got[v] = (r["means"], time.perf_counter() - t)
    import statistics

    for c, channel in enumerate("RGB"):
        ma = [m[c] for m in got[device][0]]
        mb = [m[c] for m in got[reference][0]]
        se = (statistics.variance(ma) / len(ma) + statistics.variance(mb) / len(mb)) ** 0.5
        diff = statistics.fmean(ma) - statistics.fmean(mb)
        z = abs(diff) / se if se > 0 else (0.0 if diff == 0 else float("inf"))
        good = z <= MEAN_Z_LIMIT
        ok &= good
        rows.append(
            (
                f"image mean {channel}",
                f"{device} {statistics.fmean(ma):.5f}",
                f"{reference} {statistics.fmean(mb):.5f}",
                f"z = {z:.2f} ({'ok' if good else 'MISMATCH'})",
            )
        )
    return rows, ok


def gradient_check(device, types):
    rows, ok = [], True
    for kind, _, name, _ in (c for c in GRADIENT_CASES if c[0] in types):
        r, err = run_child(device, "gradient", kind=kind)
        if r is None:
            rows.append((f"gradient {kind}.{name}", "error", "", err))
            ok = False
            continue
        ad, fd = r["ad"], r["fd"]
        gap = abs(ad - fd) / abs(fd) if fd != 0 else float("inf")
        good = all(map(lambda x: x == x and abs(x) != float("inf"), (ad, fd))) and gap <= GRADIENT_TOLERANCE
        ok &= good
        rows.append(
            (
                f"gradient {kind}.{name}",
                f"AD {ad:.6g}",
                f"FD {fd:.6g}",
                f"gap {gap:.1e} ({'ok' if good else 'MISMATCH'})",
            )
        )
    return rows, ok


def speed_table(device, repeats):
    rows, base = [], None
    for kind in ["diffuse"] + list(bench_plugin.TYPES):
        try:
            s = bench_plugin.time_in_subprocess(kind, device, 256, 64, repeats)
        except subprocess.CalledProcessError as e:
            rows.append((f"time {kind}", "error", "", (e.stderr or "").strip().splitlines()[-1:] or ""))
            continue
        base = base or s
        rows.append((f"time {kind}", f"{s:.3f} s", f"{s / base:.2f}x diffuse", ""))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--device-variant", default="cuda_ad_rgb")
    ap.add_argument("--reference-variant", default="llvm_ad_rgb")
    ap.add_argument("--res", type=int, default=64)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--repeats", type=int, default=3, help="timing: best of this many renders")
    ap.add_argument("--no-speed", action="store_true", help="skip the timing table")
    ap.add_argument(
        "--types",
        nargs="+",
        default=[c[0] for c in GRADIENT_CASES],
        help="the types whose gradient is checked (default: all)",
    )
    # Internal: one measurement in a child process.
    ap.add_argument("--child", help=argparse.SUPPRESS)
    ap.add_argument("--variant", help=argparse.SUPPRESS)
    ap.add_argument("--kind", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.child:
        return child(a)

    import mitsuba as mi

    if a.device_variant not in mi.variants():
        print(f"gpu_check: Mitsuba has no {a.device_variant} variant here; nothing to check (exit 0)")
        return 0
    probe, err = run_child(a.device_variant, "probe")
    if probe is None:
        print(f"gpu_check: {a.device_variant} cannot start on this machine ({err}); no GPU to check (exit 0)")
        return 0

    reference = a.reference_variant
    if reference != "scalar_rgb" and run_child(reference, "probe")[0] is None:
        # A GPU machine often has no libLLVM for Dr.Jit's llvm backend: scalar_rgb has the
        # same expectation and needs nothing beyond the wheels.
        print(f"gpu_check: {reference} cannot start here (no libLLVM?); scalar_rgb is the reference")
        reference = "scalar_rgb"

    rows, ok = [], True
    r, good = mean_check(a.device_variant, reference, a)
    rows += r
    ok &= good
    r, good = gradient_check(a.device_variant, a.types)
    rows += r
    ok &= good
    if not a.no_speed:
        rows += speed_table(a.device_variant, a.repeats)
    widths = [max(len(str(row[i])) for row in rows) for i in range(4)]
    print(
        f"gpu_check: {a.device_variant} against {reference} "
        f"(all_types.xml {a.res}², {a.spp} spp × {a.seeds} seeds; Cornell box for gradients and times)"
    )
    for row in rows:
        print("  " + "  ".join(str(c).ljust(w) for c, w in zip(row, widths)).rstrip())
    print("gpu_check: " + ("all checks agree" if ok else "MISMATCH (see above)"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
