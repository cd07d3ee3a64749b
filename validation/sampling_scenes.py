"""Scene-level efficiency of the models' own samplers against the cosine (docs/sampling.md,
"Scene level"), in Mitsuba's `llvm_ad_rgb` (symbolic, the plugin users run) and in matte's
renderer, measured in one run on one machine.

For every model that offers a sampler besides the cosine (`matte_mitsuba.registry.own_samplers`), each scene
(the study's four, mitsuba_scenes/sampling/grazing.xml and indirect.xml), roughness 0.3 and 1.0, and each
`sampling` (the model's own, `cosine`): K independent renders (seeds 1..K) at a small spp;
V = the per-pixel variance across the renders (unbiased, mean over pixels and channels), T =
the mean time of one render. Efficiency = 1 / (V T); the gain is the own sampler's over the
cosine's. The mean images of both samplers must agree (the expectation does not depend on the
sampler): their difference in units of its standard error is printed.

    .venv/bin/python validation/sampling_scenes.py [--renders 8] [--spp 16] [--res 96] [--models a,b] [--out DIR]

Writes DIR/sampling_scenes.json and prints a Markdown table (with the CPU).
"""

import argparse
import json
import os
import platform
import re
import subprocess
import sys
import tempfile
import time

import numpy as np

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
MATTE = os.path.join(REPO, "target", "release", "matte")
SCENES = {
    "cornell": "mitsuba_scenes/study/cornell.xml",
    "bunny": "mitsuba_scenes/study/bunny.xml",
    "room": "mitsuba_scenes/study/room.xml",
    "curved": "mitsuba_scenes/study/curved.xml",
    "grazing": "mitsuba_scenes/sampling/grazing.xml",
    "indirect": "mitsuba_scenes/sampling/indirect.xml",
}


def cpu():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return f"{line.split(':', 1)[1].strip()}, {os.cpu_count()} threads"
    except OSError:
        pass
    return platform.processor()


def scene_text(path, kind, params):
    """The scene with every `$bsdf` surface as `kind` with `params` (a roughness, `sampling`)."""
    text = open(os.path.join(REPO, path)).read()
    extra = "".join(
        f'<float name="{k}" value="{v}"/>' if isinstance(v, float) else f'<string name="{k}" value="{v}"/>'
        for k, v in params.items()
    )
    text = re.sub(r'(<bsdf type=")\$bsdf("[^>]*>)', lambda m: f"{m.group(1)}{kind}{m.group(2)}{extra}", text)
    text = text.replace('type="$bsdf"', f'type="{kind}"')
    return text


def variance_and_mean(images):
    stack = np.stack(images).astype(np.float64)
    return float(stack.var(axis=0, ddof=1).mean()), stack.mean(axis=0), stack.var(axis=0, ddof=1)


def mitsuba_renders(mi, path, kind, params, seeds, spp, res):
    folder = os.path.dirname(os.path.join(REPO, path))
    mi.file_resolver().prepend(folder)
    scene = mi.load_string(scene_text(path, kind, params), spp=str(spp), res=str(res))
    mi.render(scene, spp=spp, seed=0).numpy()  # compiles the kernels
    images, seconds = [], []
    for seed in seeds:
        t0 = time.perf_counter()
        img = np.array(mi.render(scene, spp=spp, seed=seed))
        seconds.append(time.perf_counter() - t0)
        images.append(img[..., :3])
    return images, float(np.mean(seconds))


def matte_renders(mi, path, kind, params, seeds, spp, res):
    folder = os.path.dirname(os.path.join(REPO, path))
    images, seconds = [], []
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(folder, f".sampling_{os.getpid()}.xml")
        with open(scene, "w") as f:
            f.write(scene_text(path, kind, params))
        try:
            for seed in seeds:
                out = os.path.join(tmp, f"{seed}.exr")
                t0 = time.perf_counter()
                subprocess.run(
                    [
                        MATTE,
                        "render",
                        scene,
                        "-q",
                        "--spp",
                        str(spp),
                        "--seed",
                        str(seed),
                        "-D",
                        f"res={res}",
                        "-o",
                        out,
                    ],
                    check=True,
                    capture_output=True,
                )
                seconds.append(time.perf_counter() - t0)
                images.append(np.array(mi.Bitmap(out))[..., :3])
        finally:
            os.remove(scene)
    return images, float(np.mean(seconds))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--renders", type=int, default=8)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--res", type=int, default=96)
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--models", default="", help="comma-separated types (default: every model with its own sampler)")
    ap.add_argument("--out", default="bench_out")
    a = ap.parse_args()

    import mitsuba as mi

    mi.set_variant("llvm_ad_rgb")
    import matte_mitsuba
    from matte_mitsuba import registry

    matte_mitsuba.register()

    own = [
        (m, s)
        for m in registry.MODELS
        for s in registry.own_samplers(m)
        if not a.models or m["name"] in a.models.split(",")
    ]
    seeds = list(range(1, a.renders + 1))
    rows = []
    for m, own_sampler in own:
        rough = registry.numeric_parameters(m)[0]["name"]
        for scene in a.scenes.split(","):
            for r in (0.3, 1.0):
                for renderer, run in (("mitsuba llvm_ad_rgb", mitsuba_renders), ("matte", matte_renders)):
                    got = {}
                    for sampling in (own_sampler, "cosine"):
                        images, seconds = run(
                            mi, SCENES[scene], m["name"], {rough: r, "sampling": sampling}, seeds, a.spp, a.res
                        )
                        v, mean, var = variance_and_mean(images)
                        got[sampling] = (v, seconds, mean, var)
                    (v1, t1, m1, s1), (v0, t0, m0, s0) = got[own_sampler], got["cosine"]
                    se = np.sqrt((s1 + s0) / len(seeds)).mean()
                    z = float(abs(m1.mean() - m0.mean()) / (np.sqrt(((s1 + s0) / len(seeds)).mean() / m1.size)))
                    row = {
                        "model": m["name"],
                        "sampler": own_sampler,
                        "scene": scene,
                        "roughness": r,
                        "renderer": renderer,
                        "variance": v1,
                        "variance_cosine": v0,
                        "seconds": t1,
                        "seconds_cosine": t0,
                        "variance_ratio": v0 / v1,
                        "time_ratio": t1 / t0,
                        "efficiency_gain": (v0 * t0) / (v1 * t1),
                        "mean_difference_z": z,
                        "pixel_standard_error": float(se),
                    }
                    rows.append(row)
                    print(
                        f"{m['name']} {scene} r={r} {renderer}: variance ratio {row['variance_ratio']:.2f}, "
                        f"time ratio {row['time_ratio']:.2f}, gain {row['efficiency_gain']:.2f} (means z={z:.1f})",
                        file=sys.stderr,
                    )
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "sampling_scenes.json"), "w") as f:
        json.dump({"machine": cpu(), "renders": a.renders, "spp": a.spp, "res": a.res, "rows": rows}, f, indent=1)
    print(f"machine: {cpu()}; {a.renders} renders of {a.spp} spp at {a.res}² per configuration\n")
    print(
        "| model | scene | roughness | renderer | variance ratio (cosine / own) | time ratio (own / cosine) | efficiency gain |"
    )
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(
            f"| {r['model']} | {r['scene']} | {r['roughness']} | {r['renderer']} | {r['variance_ratio']:.2f} | "
            f"{r['time_ratio']:.2f} | {r['efficiency_gain']:.2f} |"
        )


if __name__ == "__main__":
    main()
