"""Showcase of ``matte fit``: recover a σ map and a reflectance map of an Oren–Nayar plane from
images, and show how the choice of light/view configurations decides whether σ and ρ can be
told apart.

    .venv/bin/python validation/experiments/fit_showcase.py [-o fit_showcase_out] [--iterations 300]

The truth: a plane with a 16×16-texel σ map (smooth blobs, 0.1 to 0.8 rad) and a 16×16 RGB
reflectance map (0.2 to 0.8), qualitative Oren–Nayar, lit by a directional light, seen by a
64² perspective camera; direct lighting only (a lone plane has no interreflection). The start:
σ = 0.001 (Lambert) and ρ = 0.5 everywhere. Three sets of configurations (each one image per
configuration, the same freed parameters for all):

* ``backscatter``: light along the view direction (retro-reflection), views at 0°, 30°, 50°,
  65° from the normal;
* ``frontal``: views and lights within 15° of the normal;
* ``mixed``: views at 0°, 40°, 65° with the light at the camera, opposite it (forward
  scattering) and to the side.

Oren–Nayar at normal incidence is `ρ A(σ)/π`, so frontal images constrain only the product:
σ and ρ trade off. Back-scattering adds `B(σ) sin θ tan θ`, which separates them. The script
reports per set: mean |σ error| (rad), mean |ρ error|, and the correlation of the per-texel
σ and ρ errors (close to +1 is the trade-off: a σ too high lowers A(σ), which a ρ too high
compensates). Targets come from the truth scene
rendered at 512 spp with seeds the fit never uses; the oracle is the known truth maps.
Outputs: one ``matte fit`` folder per set (``index.html``), ``showcase.json`` and
``showcase.html`` with the comparison figure ``maps.png``.
"""

import argparse
import json
import math
import os
import sys

import numpy as np

RES_TEX = 16

SCENE = """<scene version="3.0.0">
    <default name="ox" value="0"/><default name="oy" value="0"/><default name="oz" value="3"/>
    <default name="lx" value="0"/><default name="ly" value="0"/><default name="lz" value="-1"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="$ox, $oy, $oz" target="0, 0, 0" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="64"/>
            <rfilter type="box"/></film>
    </sensor>
    <emitter type="directional">
        <vector name="direction" value="$lx, $ly, $lz"/>
        <rgb name="irradiance" value="3"/>
    </emitter>
    <shape type="rectangle" id="plane">
        <bsdf type="oren_nayar">
            <texture type="bitmap" name="sigma">
                <string name="filename" value="{sigma}"/>
                <boolean name="raw" value="true"/>
                <string name="filter_type" value="nearest"/>
            </texture>
            <texture type="bitmap" name="reflectance">
                <string name="filename" value="{rho}"/>
                <boolean name="raw" value="true"/>
                <string name="filter_type" value="nearest"/>
            </texture>
        </bsdf>
    </shape>
</scene>
"""


def direction(theta_deg, phi_deg):
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])


def config(view, light, distance=3.2):
    """Camera at `view` = (θ, φ) degrees from the normal, light arriving from `light` = (θ, φ)."""
    o = distance * direction(*view)
    d = -direction(*light)  # the light travels towards the plane
    # A camera exactly above would make lookat's up = z degenerate: nudge it.
    if view[0] == 0:
        o = distance * direction(0.5, view[1])
    return ",".join(f"{k}={v:.6f}" for k, v in zip(("ox", "oy", "oz", "lx", "ly", "lz"), (*o, *d)))


SETS = {
    "backscatter": [config((t, 20), (t, 20)) for t in (0, 30, 50, 65)],
    "frontal": [
        config((v, p), (l, q)) for v, p, l, q in ((0, 0, 10, 90), (10, 200, 0, 0), (15, 100, 12, 300), (5, 30, 15, 180))
    ],
    "mixed": [
        config((0, 0), (0, 0)),
        config((40, 20), (40, 20)),
        config((65, 250), (65, 250)),
        config((40, 20), (45, 200)),
        config((65, 250), (30, 70)),
        config((40, 110), (60, 20)),
    ],
}


def truth_maps():
    y, x = np.mgrid[0:RES_TEX, 0:RES_TEX] / (RES_TEX - 1)
    sigma = 0.1 + 0.7 * np.clip(
        0.55 * np.exp(-((x - 0.3) ** 2 + (y - 0.35) ** 2) / 0.04)
        + 0.75 * np.exp(-((x - 0.7) ** 2 + (y - 0.65) ** 2) / 0.06)
        + 0.25 * (x > 0.8) * (y < 0.3),
        0,
        1,
    )
    rho = np.stack([0.2 + 0.6 * x, 0.2 + 0.6 * y, 0.5 + 0.3 * np.sin(6 * x) * np.cos(5 * y)], axis=2)
    return sigma.astype(np.float32), rho.astype(np.float32)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("-o", "--output", default="fit_showcase_out")
    ap.add_argument("--iterations", type=int, default=300)
    ap.add_argument("--spp", type=int, default=8)
    ap.add_argument("--lr", type=float, default=0.03)
    ap.add_argument("--sets", default="backscatter,frontal,mixed")
    args = ap.parse_args()

    import mitsuba as mi

    mi.set_variant("llvm_ad_rgb")
    from matte_mitsuba.fit import main as fit_main

    out = os.path.abspath(args.output)
    os.makedirs(out, exist_ok=True)
    sigma, rho = truth_maps()
    paths = {}
    for name, arr in (
        ("truth_sigma", sigma[..., None]),
        ("truth_rho", rho),
        ("start_sigma", np.full((RES_TEX, RES_TEX, 1), 1e-3, np.float32)),
        ("start_rho", np.full((RES_TEX, RES_TEX, 3), 0.5, np.float32)),
    ):
        paths[name] = os.path.join(out, f"{name}.exr")
        mi.Bitmap(arr).write(paths[name])
    for which in ("truth", "start"):
        with open(os.path.join(out, f"{which}.xml"), "w") as f:
            f.write(SCENE.format(sigma=paths[f"{which}_sigma"], rho=paths[f"{which}_rho"]))

    results = {}
    for set_name in args.sets.split(","):
        folder = os.path.join(out, set_name)
        argv = [
            os.path.join(out, "start.xml"),
            "--target-scene",
            os.path.join(out, "truth.xml"),
            "--param",
            "plane.bsdf.sigma.data",
            "--param",
            "plane.bsdf.reflectance.data",
            "--iterations",
            str(args.iterations),
            "--lr",
            str(args.lr),
            "--spp",
            str(args.spp),
            "--target-spp",
            "512",
            "--max-depth",
            "2",
            "-o",
            folder,
        ]
        for c in SETS[set_name]:
            argv += ["--config", c]
        print(f"showcase: {set_name} ({len(SETS[set_name])} configurations)", file=sys.stderr)
        if fit_main(argv) != 0:
            sys.exit(f"showcase: the fit of {set_name} failed")
        fit_sigma = np.array(mi.Bitmap(os.path.join(folder, "plane.bsdf.sigma.data.exr")), dtype=np.float64).reshape(
            RES_TEX, RES_TEX, -1
        )[..., 0]
        fit_rho = np.array(
            mi.Bitmap(os.path.join(folder, "plane.bsdf.reflectance.data.exr")), dtype=np.float64
        ).reshape(RES_TEX, RES_TEX, 3)
        e_sigma = fit_sigma - sigma
        e_rho = (fit_rho - rho).mean(axis=2)
        corr = float(np.corrcoef(e_sigma.ravel(), e_rho.ravel())[0, 1])
        with open(os.path.join(folder, "fit.json")) as f:
            fj = json.load(f)
        results[set_name] = {
            "configurations": len(SETS[set_name]),
            "mean_abs_sigma_error_rad": float(np.abs(e_sigma).mean()),
            "max_abs_sigma_error_rad": float(np.abs(e_sigma).max()),
            "mean_abs_rho_error": float(np.abs(fit_rho - rho).mean()),
            "sigma_rho_error_correlation": corr,
            "final_loss": fj["loss"][-1],
            "seconds": fj.get("seconds"),
            "fit_sigma": fit_sigma.tolist(),
            "fit_rho_mean": fit_rho.mean(axis=2).tolist(),
        }
        r = results[set_name]
        print(
            f"showcase: {set_name}: mean |σ error| {r['mean_abs_sigma_error_rad']:.4f} rad, "
            f"mean |ρ error| {r['mean_abs_rho_error']:.4f}, corr(σ err, ρ err) {corr:+.2f}",
            file=sys.stderr,
        )

    summary = {
        "iterations": args.iterations,
        "spp": args.spp,
        "lr": args.lr,
        "texels": RES_TEX,
        "image": 64,
        "goal_mean_abs_sigma_error_rad": 0.02,
        "sets": {k: {kk: vv for kk, vv in v.items() if not kk.startswith("fit_")} for k, v in results.items()},
    }
    with open(os.path.join(out, "showcase.json"), "w") as f:
        json.dump(summary, f, indent=1)
    figure(out, sigma, rho, results)
    page(out, summary)
    print(os.path.join(out, "showcase.html"))


def figure(out, sigma, rho, results):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(results)
    fig, ax = plt.subplots(2, n + 1, figsize=(3.2 * (n + 1), 6.2), dpi=100)
    ax[0, 0].imshow(sigma, vmin=0, vmax=0.9, cmap="viridis")
    ax[0, 0].set_title("truth σ (rad)")
    ax[1, 0].imshow(rho.mean(axis=2), vmin=0.1, vmax=0.9, cmap="gray")
    ax[1, 0].set_title("truth ρ (channel mean)")
    for k, (name, r) in enumerate(results.items(), start=1):
        im = ax[0, k].imshow(np.array(r["fit_sigma"]), vmin=0, vmax=0.9, cmap="viridis")
        ax[0, k].set_title(f"{name}: σ, mean |err| {r['mean_abs_sigma_error_rad']:.3f}", fontsize=9)
        ax[1, k].imshow(np.array(r["fit_rho_mean"]), vmin=0.1, vmax=0.9, cmap="gray")
        ax[1, k].set_title(
            f"ρ, mean |err| {r['mean_abs_rho_error']:.3f}; corr {r['sigma_rho_error_correlation']:+.2f}", fontsize=9
        )
    for a in ax.ravel():
        a.set_axis_off()
    fig.colorbar(im, ax=ax[0, :].tolist(), shrink=0.8)
    fig.savefig(os.path.join(out, "maps.png"))
    plt.close(fig)


def page(out, summary):
    rows = "".join(
        f"<tr><td>{k}</td><td>{v['configurations']}</td><td>{v['mean_abs_sigma_error_rad']:.4f}</td>"
        f"<td>{v['max_abs_sigma_error_rad']:.3f}</td><td>{v['mean_abs_rho_error']:.4f}</td>"
        f"<td>{v['sigma_rho_error_correlation']:+.2f}</td><td><a href='{k}/index.html'>{k}/index.html</a></td></tr>"
        for k, v in summary["sets"].items()
    )
    with open(os.path.join(out, "showcase.html"), "w") as f:
        f.write(f"""<!doctype html><meta charset=utf-8><title>matte fit showcase</title>
<style>body{{font:14px sans-serif;margin:2em}}td,th{{border:1px solid #ccc;padding:4px 8px}}table{{border-collapse:collapse}}</style>
<h1>matte fit: σ and ρ maps of an Oren–Nayar plane</h1>
<p>{summary["texels"]}² texel maps, {summary["image"]}² images, {summary["iterations"]} Adam iterations
(lr {summary["lr"]}), {summary["spp"]} spp per render; goal: mean |σ error| &lt; {summary["goal_mean_abs_sigma_error_rad"]} rad.</p>
<table><tr><th>configurations</th><th>images</th><th>mean |σ err| (rad)</th><th>max |σ err|</th>
<th>mean |ρ err|</th><th>corr(σ err, ρ err)</th><th>fit report</th></tr>{rows}</table>
<img src='maps.png'>
""")


if __name__ == "__main__":
    main()
