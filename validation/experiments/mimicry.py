"""Can one diffuse model mimic another? The 5×5 mimicry table.

    .venv/bin/python validation/experiments/mimicry.py [-o mimicry_out] [--scenes cornell,sphere]

For the paper's four models and EON (lambert, wolff, oren_nayar, eon, ginneken) at the study's
parameters (the plugins' defaults: Wolff IOR 1.4, Oren–Nayar σ 0.3, EON r 0.3, van Ginneken
m 0.3; docs/study.md), the script renders a target with each model, then fits every model
to every target with ``matte_mitsuba.fit`` (Adam on ``prb`` renders): the reflectance of every
material and the model's own shape parameter (Wolff ``int_ior``, Oren–Nayar ``sigma``, EON and
van Ginneken ``roughness``; Lambert has only the reflectance). What is left after the fit is
what no tuning of that model can reproduce. Two scenes:

* ``cornell``: the study's Cornell box (``mitsuba_scenes/study/cornell.xml``, three materials,
  each with its own reflectance and shape parameter), 32², ``prb`` max_depth 3 (direct light
  and one interreflection, as ``matte fit``'s default);
* ``sphere``: a sphere (reflectance 0.8, 0.6, 0.4) under one directional light, no other
  light, seen from 4.5 radii, 32², direct lighting, in three images that share the fitted
  parameters: phase angle (light–sphere–camera) 0° (light at the camera: back-scattering,
  where rough models flatten the disc), 75° (side light: the terminator's fall-off) and 135°
  (light from behind: a crescent of forward scattering at grazing angles, where Fresnel and
  shadowing differ). A sphere shows every incidence and view angle of its phase angle at once.

Every fit starts from the study's shape parameter and the scene's reflectances scaled per
channel to the target's mean brightness (one 32-spp render; Wolff's K divides by n², so its
reflectances differ from Lambert's for the same image), and runs the same iterations (Adam,
learning rate decaying geometrically, the reflectances' a quarter of the shape parameter's).
So a diagonal cell starts at its optimum: its residual is what the fit's own noise leaves
(parameters jitter with the noisy 8-spp gradients), the floor for the other cells of its row
next to the render-noise floor. A residual is an upper bound on how closely the fitted model
can mimic the target (a longer fit can only lower it); the fitted parameters say where it
went. Starting away from the truth, the ρ–shape trade-offs (ρ·A(σ) for Oren–Nayar, ρ against
n² for Wolff) make fits of this budget stop early in a valley (``tests/plugin/test_mimicry.py``
checks a recovery on the sphere, where the three phase angles separate them). The
residual is measured on a fresh render of the fitted model at the target's spp with a seed the
target never used, against the target:

* **relative RMSE** ‖fit − target‖₂ / ‖target‖₂ over all pixels and channels (all images of
  the scene together);
* **worst region**: the largest |mean(fit) − mean(target)| / mean(target) of luminance over
  blocks of 1/8 of the image side (4×4 pixels at 32²) whose target luminance is at least 25 %
  of the image's mean block;
* the **noise floor** of both: the same numbers for the target against a second target rendered
  with another seed. A residual at its floor means the fitted model is indistinguishable from
  the target at this noise level; ``excess`` = √(rmse² − floor²) estimates the part of the
  relative RMSE that is model mismatch, not noise.

Outputs in ``-o``: ``mimicry.json`` (every number), ``mimicry.md`` (the tables; bold: above
twice the noise floor), ``index.html`` (the tables per scene, the
grid of difference images, a strip per pair), ``<scene>/grid.png``, ``<scene>/<target>/
<fitted>.png`` (target | fit | relative difference per image) and the ``matte fit`` folder of
every pair (``<scene>/<target>/<fitted>/index.html``).
"""

import argparse
import html
import json
import math
import os
import sys
import time

import numpy as np

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

MODELS = ("lambert", "wolff", "oren_nayar", "eon", "ginneken")
LABELS = {"lambert": "Lambert", "wolff": "Wolff", "oren_nayar": "Oren–Nayar", "eon": "EON", "ginneken": "van Ginneken"}
# Each model's shape parameter and the study's value (the plugin's default, where every fit
# starts). Lambert has none.
SHAPE = {
    "lambert": None,
    "wolff": ("int_ior", 1.4),
    "oren_nayar": ("sigma", 0.3),
    "eon": ("roughness", 0.3),
    "ginneken": ("roughness", 0.3),
}
BLOCKS = 8  # worst-region blocks per image side
BLOCK_MIN = 0.25  # blocks darker than this fraction of the image's mean block are skipped

SPHERE = """<scene version="3.0.0">
    <!-- matte mimicry: a sphere under one directional light (validation/experiments/mimicry.py). -->
    <default name="bsdf" value="lambert"/>
    <default name="res" value="64"/>
    <default name="lx" value="0"/><default name="lz" value="-1"/>
    <sensor type="perspective">
        <float name="fov" value="30"/>
        <transform name="to_world"><lookat origin="0, 0, 4.5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/>
            <rfilter type="box"/></film>
    </sensor>
    <emitter type="directional">
        <vector name="direction" value="$lx, 0, $lz"/>
        <rgb name="irradiance" value="3"/>
    </emitter>
    <shape type="sphere" id="ball">
        <float name="radius" value="1"/>
        <bsdf type="$bsdf">
            <rgb name="reflectance" value="0.8, 0.6, 0.4"/>
        </bsdf>
    </shape>
</scene>
"""


def sphere_config(phase_deg):
    """Defines for a light at `phase_deg` from the camera direction (+z), in the x–z plane."""
    g = math.radians(phase_deg)
    return {"lx": f"{-math.sin(g):.7f}", "lz": f"{-math.cos(g):.7f}"}


def scene_specs(out, res):
    """The two scenes: file, configurations (defines per image), materials (the prefix of their
    SceneParameters keys), prb depth."""
    sphere_file = os.path.join(out, "sphere.xml")
    return {
        "cornell": {
            "file": os.path.join(REPO, "mitsuba_scenes", "study", "cornell.xml"),
            "configs": [{"res": str(res)}],
            "config_names": ["Cornell box"],
            "materials": ("white", "green", "red"),
            "max_depth": 3,
        },
        "sphere": {
            "file": sphere_file,
            "write": SPHERE,
            "configs": [dict(sphere_config(g), res=str(res)) for g in (0, 75, 135)],
            "config_names": ["phase 0°", "phase 75°", "phase 135°"],
            "materials": ("ball.bsdf",),
            "max_depth": 2,
        },
    }


def free_keys(model, materials):
    """The keys a fit of `model` frees (each starts at the scene's value: the scene's
    reflectances and the study's shape parameter)."""
    keys = []
    for m in materials:
        keys.append(f"{m}.reflectance.value")
        if SHAPE[model]:
            keys.append(f"{m}.{SHAPE[model][0]}")
    return keys


# -- Error measures (numpy; images are lists of H×W×3 arrays, one per configuration) ----------


def luminance(img):
    return img[..., 0] * 0.2126 + img[..., 1] * 0.7152 + img[..., 2] * 0.0722


def relative_rmse(images, targets):
    """‖a − b‖₂ / ‖b‖₂ over every pixel and channel of every image."""
    num = sum(float(np.sum((a - b) ** 2)) for a, b in zip(images, targets))
    den = sum(float(np.sum(b**2)) for b in targets)
    return math.sqrt(num / den)


def block_means(y, block):
    h, w = y.shape[0] // block * block, y.shape[1] // block * block
    return y[:h, :w].reshape(h // block, block, w // block, block).mean(axis=(1, 3))


def worst_region(images, targets, blocks=BLOCKS, min_fraction=BLOCK_MIN):
    """The largest relative luminance error of a block mean, over the blocks at least
    `min_fraction` as bright as the image's mean block (a mean, not the brightest block, so that
    a visible light does not exclude the walls): (error, image index, block row, col)."""
    worst = (0.0, -1, -1, -1)
    block = max(1, targets[0].shape[0] // blocks)
    for c, (a, b) in enumerate(zip(images, targets)):
        ma, mb = block_means(luminance(a), block), block_means(luminance(b), block)
        valid = mb >= min_fraction * mb.mean()
        rel = np.where(valid, np.abs(ma - mb) / np.where(valid, mb, 1.0), 0.0)
        i, j = np.unravel_index(int(np.argmax(rel)), rel.shape)
        if rel[i, j] > worst[0]:
            worst = (float(rel[i, j]), c, int(i), int(j))
    return worst


def excess(value, floor):
    """The part of a relative RMSE above the noise floor (independent errors add in squares)."""
    return math.sqrt(max(0.0, value * value - floor * floor))


# -- Rendering -------------------------------------------------------------------------------


def render_model(mi, spec, model, spp, seed, values=None):
    """One render per configuration of `spec` with `model`; `values` (key → list) overrides
    parameters (the fitted ones). Returns numpy arrays."""
    integrator = mi.load_dict({"type": "prb", "max_depth": spec["max_depth"]})
    out = []
    for c, defines in enumerate(spec["configs"]):
        scene = mi.load_file(spec["file"], bsdf=model, **defines)
        if values:
            p = mi.traverse(scene)
            for k, v in values.items():
                p[k] = type(p[k])(*v) if len(v) > 1 else type(p[k])(v[0])
            p.update()
        img = mi.render(scene, integrator=integrator, spp=spp, seed=seed + c)
        out.append(np.array(img, dtype=np.float64))
    return out


def matched_reflectances(mi, spec, model, targets, spp=32):
    """The scene's reflectances scaled per channel so that `model`'s render has the targets'
    mean (clamped to [0.001, 1]): the fit's start. Models with other normalisations (Wolff's K
    divides by n²) need other reflectances for the same brightness; this first step leaves
    the fit the shape to find, not the scale."""
    renders = render_model(mi, spec, model, spp, seed=4_000_000)
    ratio = sum(t.sum(axis=(0, 1)) for t in targets) / sum(r.sum(axis=(0, 1)) for r in renders)
    p = mi.traverse(mi.load_file(spec["file"], bsdf=model, **spec["configs"][0]))
    return {
        f"{m}.reflectance.value": np.clip(np.array(p[f"{m}.reflectance.value"]).ravel() * ratio, 0.001, 1.0)
        for m in spec["materials"]
    }


def fit_pair(spec, target_files, model, folder, args, start_rho):
    """Fits `model` to the targets with matte_mitsuba.fit, starting from the reflectances
    `start_rho` and the study's shape parameter; returns its fit.json."""
    from matte_mitsuba.fit import main as fit_main

    keys = free_keys(model, spec["materials"])
    argv = [
        spec["file"],
        "--iterations",
        str(args.iterations),
        "--lr",
        str(args.lr),
        "--lr-final",
        str(args.lr_final),
        "--spp",
        str(args.spp),
        "--max-depth",
        str(spec["max_depth"]),
        "--seed",
        str(args.seed),
        "-o",
        folder,
        "--quiet",
    ]
    for k in keys:
        argv += ["--param", k]
        if k in start_rho:
            argv += [
                "--init",
                f"{k}=" + ",".join(f"{x:.6g}" for x in start_rho[k]),
                "--lr-factor",
                f"{k}={args.rho_lr_factor}",
            ]
        elif model in args.start:
            argv += ["--init", f"{k}={args.start[model]}"]
    for defines, t in zip(spec["configs"], target_files):
        argv += ["--config", ",".join(f"{k}={v}" for k, v in dict(defines, bsdf=model).items()), "--target", t]
    if fit_main(argv) != 0:
        raise SystemExit(f"mimicry: the fit of {model} in {folder} failed")
    with open(os.path.join(folder, "fit.json")) as f:
        return json.load(f)


def noise_floor(mi, spec, model, target, target_spp):
    """The error measures of `target` against a second target rendered with another seed."""
    second = render_model(mi, spec, model, target_spp, seed=2_000_000)
    return {"relative_rmse": relative_rmse(second, target), "worst_region": worst_region(second, target)[0]}


def cell(fit_json, fitted, target, floor, t, m, seconds, start_rho=None):
    """One table cell: the fitted render's residual against the target, and the fit."""
    values = {k: v["value"] for k, v in fit_json["fitted"].items()}
    rmse = relative_rmse(fitted, target)
    worst = worst_region(fitted, target)
    ranges = fit_json["ranges"]
    at_bound = sorted(
        k for k, v in values.items() if any(abs(x - ranges[k][0]) < 1e-6 or abs(x - ranges[k][1]) < 1e-6 for x in v)
    )
    return {
        "relative_rmse": rmse,
        "excess": excess(rmse, floor["relative_rmse"]),
        "worst_region": worst[0],
        "worst_region_at": {"image": worst[1], "block_row": worst[2], "block_col": worst[3]},
        "fitted": values,
        "start_reflectance": {k: v.tolist() for k, v in start_rho.items()} if start_rho else None,
        "at_bound": at_bound,
        "loss_first": fit_json["loss"][0],
        "loss_last": fit_json["loss"][-1],
        "seconds": seconds,
        "fit_report": os.path.join(t, m, "index.html"),
        "strip": os.path.join(t, f"{m}.png"),
    }


def scene_summary(spec, floors, cells):
    return {
        "file": os.path.relpath(spec["file"], REPO)
        if spec["file"].startswith(REPO)
        else os.path.basename(spec["file"]),
        "images": spec["config_names"],
        "materials": list(spec["materials"]),
        "max_depth": spec["max_depth"],
        "noise_floor": floors,
        "cells": cells,
    }


def log_cell(name, t, m, c, floor):
    print(
        f"mimicry: {name}: target {t:<10} fitted {m:<10} rel. RMSE {100 * c['relative_rmse']:6.2f} % "
        f"(floor {100 * floor['relative_rmse']:.2f} %), worst region {100 * c['worst_region']:6.2f} % "
        f"(floor {100 * floor['worst_region']:.2f} %), {c['seconds']:.0f} s",
        file=sys.stderr,
        flush=True,
    )


def run_scene(mi, name, spec, out, args):
    """Targets (the rows `args.targets`), their fits by every model and the residuals."""
    folder = os.path.join(out, name)
    os.makedirs(folder, exist_ok=True)
    if "write" in spec:
        with open(spec["file"], "w") as f:
            f.write(spec["write"])
    models = args.models
    targets, target_files, floors = {}, {}, {}
    for t in args.targets:
        targets[t] = render_model(mi, spec, t, args.target_spp, seed=1_000_000)
        os.makedirs(os.path.join(folder, t), exist_ok=True)
        target_files[t] = []
        for c, img in enumerate(targets[t]):
            path = os.path.join(folder, t, f"target_{c}.exr")
            mi.Bitmap(img.astype(np.float32)).write(path)
            target_files[t].append(path)
        floors[t] = noise_floor(mi, spec, t, targets[t], args.target_spp)
        print(
            f"mimicry: {name}: target {t}: noise floor {100 * floors[t]['relative_rmse']:.2f} % "
            f"(worst region {100 * floors[t]['worst_region']:.2f} %)",
            file=sys.stderr,
            flush=True,
        )
    cells = {}
    for t in args.targets:
        cells[t] = {}
        for m in models:
            started = time.time()
            start_rho = matched_reflectances(mi, spec, m, targets[t])
            fj = fit_pair(spec, target_files[t], m, os.path.join(folder, t, m), args, start_rho)
            values = {k: v["value"] for k, v in fj["fitted"].items()}
            fitted = render_model(mi, spec, m, args.target_spp, seed=3_000_000, values=values)
            np.save(os.path.join(folder, t, m, "fitted_render.npy"), np.stack(fitted).astype(np.float32))
            cells[t][m] = cell(fj, fitted, targets[t], floors[t], t, m, time.time() - started, start_rho)
            log_cell(name, t, m, cells[t][m], floors[t])
    pictures(folder, args.targets, models, targets, cells, args.diff_range)
    return scene_summary(spec, floors, cells)


def collect_scene(mi, name, spec, out, args):
    """The summary of one scene rebuilt from what runs left in its folder (rows run by separate
    processes with --targets, or a run stopped early): the saved targets, each pair's fit.json
    and fitted render; the noise floors re-rendered with the run's seed. Pairs without a fitted
    render are left out."""
    folder = os.path.join(out, name)
    if "write" in spec and not os.path.exists(spec["file"]):
        with open(spec["file"], "w") as f:
            f.write(spec["write"])
    rows = [t for t in MODELS if os.path.exists(os.path.join(folder, t, "target_0.exr"))]
    targets = load_targets(folder, rows, len(spec["configs"]))
    floors = {t: noise_floor(mi, spec, t, targets[t], args.target_spp) for t in rows}
    cells = {}
    for t in rows:
        for m in MODELS:
            pair = os.path.join(folder, t, m)
            if not os.path.exists(os.path.join(pair, "fitted_render.npy")):
                continue
            with open(os.path.join(pair, "fit.json")) as f:
                fj = json.load(f)
            fitted = list(np.load(os.path.join(pair, "fitted_render.npy")).astype(np.float64))
            cells.setdefault(t, {})[m] = cell(fj, fitted, targets[t], floors[t], t, m, fj.get("seconds"))
            log_cell(name, t, m, cells[t][m], floors[t])
    columns = [m for m in MODELS if any(m in r for r in cells.values())]
    pictures(folder, list(cells), columns, targets, cells, args.diff_range)
    return scene_summary(spec, {t: floors[t] for t in cells}, cells)


# -- Pictures --------------------------------------------------------------------------------


def pictures(folder, rows, columns, targets, cells, value_range):
    """The strip of every pair in `cells` and the scene's grid, from the targets and the saved
    fitted renders."""
    for t in rows:
        for m in columns:
            if m in cells.get(t, {}):
                fitted = np.load(os.path.join(folder, t, m, "fitted_render.npy")).astype(np.float64)
                strip_png(os.path.join(folder, t, f"{m}.png"), targets[t], fitted, value_range)
    grid_png(os.path.join(folder, "grid.png"), rows, columns, targets, folder, cells, value_range)


def load_targets(folder, models, count):
    import mitsuba as mi

    return {
        t: [np.array(mi.Bitmap(os.path.join(folder, t, f"target_{c}.exr")), dtype=np.float64) for c in range(count)]
        for t in models
    }


def srgb(img):
    x = np.clip(img, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def difference_rgb(a, b, value_range):
    """(L_a − L_b) / L_b as red (a brighter) / blue (a darker), ±`value_range` saturates; black
    where the target is dark (below 5 % of its mean luminance)."""
    import matplotlib

    la, lb = luminance(a), luminance(b)
    dark = lb < 0.05 * max(lb.mean(), 1e-12)
    rel = np.where(dark, 0.0, (la - lb) / np.where(dark, 1.0, lb))
    rgb = matplotlib.colormaps["RdBu_r"](0.5 + 0.5 * np.clip(rel / value_range, -1, 1))[..., :3]
    rgb[dark] = 0.0
    return rgb


def strip_png(path, targets, fitted, value_range):
    """Per image one row: target | fitted render | relative difference."""
    import mitsuba as mi

    rows = [
        np.concatenate(
            [
                srgb(t),
                np.full((t.shape[0], 2, 3), 1.0),
                srgb(f),
                np.full((t.shape[0], 2, 3), 1.0),
                difference_rgb(f, t, value_range),
            ],
            axis=1,
        )
        for t, f in zip(targets, fitted)
    ]
    gap = np.full((2, rows[0].shape[1], 3), 1.0)
    img = np.concatenate(sum(([r, gap] for r in rows), [])[:-1], axis=0)
    mi.Bitmap((np.clip(img, 0, 1) * 255 + 0.5).astype(np.uint8), mi.Bitmap.PixelFormat.RGB).write(path)


def grid_png(path, rows, columns, targets, folder, cells, value_range):
    """Rows: target model (its target, then the difference of each fitted model's render)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(columns)
    fig, ax = plt.subplots(
        len(rows),
        n + 1,
        figsize=(1.9 * (n + 1) * len(targets[rows[0]]) ** 0.5, 1.9 * len(rows) + 0.6),
        dpi=110,
        squeeze=False,
    )
    for i, t in enumerate(rows):
        ax[i, 0].imshow(srgb(np.concatenate(targets[t], axis=1)))
        ax[i, 0].set_title(f"target: {LABELS[t]}", fontsize=8)
        for j, m in enumerate(columns, start=1):
            if m not in cells.get(t, {}):
                continue
            fitted = np.load(os.path.join(folder, t, m, "fitted_render.npy")).astype(np.float64)
            diff = np.concatenate([difference_rgb(f, g, value_range) for f, g in zip(fitted, targets[t])], axis=1)
            ax[i, j].imshow(diff)
            c = cells[t][m]
            ax[i, j].set_title(f"{LABELS[m]}: {100 * c['relative_rmse']:.1f} %", fontsize=8)
    for a in ax.ravel():
        a.set_axis_off()
    fig.suptitle(
        f"fitted − target, relative luminance, blue −{100 * value_range:.0f} % … red +{100 * value_range:.0f} %",
        fontsize=9,
    )
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


# -- Report ----------------------------------------------------------------------------------


def cell_colour(value, floor):
    """Green at the noise floor, through yellow to red at 5× the floor and above."""
    r = min(max((value / floor - 1.0) / 4.0, 0.0), 1.0) if floor > 0 else 1.0
    hue = 120 * (1 - r)
    return f"hsl({hue:.0f},70%,88%)"


def shape_text(model, values):
    if not SHAPE[model]:
        return ""
    name = SHAPE[model][0]
    vals = [v[0] for k, v in values.items() if k.endswith("." + name)]
    return f"{name} " + ", ".join(f"{v:.3g}" for v in vals)


def write_html(out, summary):
    e = html.escape
    s = summary["settings"]
    parts = [
        f"""<!doctype html><html><head><meta charset="utf-8"><title>matte mimicry</title><style>
body{{font-family:system-ui,sans-serif;margin:24px;color:#222;max-width:1400px}} img{{max-width:100%;border:1px solid #ddd}}
table{{border-collapse:collapse;font-size:14px;margin:8px 0}} td,th{{padding:3px 10px;border-bottom:1px solid #eee;text-align:right}}
td{{white-space:nowrap}} th:first-child,td:first-child{{text-align:left}} .scene{{border-top:1px solid #ccc;padding-top:12px;margin-top:16px}}
.small{{font-size:13px;color:#555}} img.px{{image-rendering:pixelated;width:{4 * s["res"]}px;max-width:none}}
</style></head><body><h1>matte mimicry: can one diffuse model mimic another?</h1>
<p>Each target is rendered with one model at the study's parameters (Wolff IOR 1.4, Oren–Nayar σ 0.3, EON r 0.3,
van Ginneken m 0.3) at {s["target_spp"]} spp; every model is then fitted to it (<code>matte_mitsuba.fit</code>: Adam,
{s["iterations"]} iterations, learning rate {s["lr"]} decaying to {s["lr_final"]}, {s["spp"]} spp per step, {s["res"]}²
images): every material's reflectance and the model's shape parameter, starting from the model as the study uses it
(the study's parameter, the scene's reflectances scaled per channel to the target's mean; a diagonal cell starts at its
optimum, so its residual is the fit's own noise); the reflectances' learning rate is {s["rho_lr_factor"]} of the shape
parameter's.
Rows: the target's model; columns: the fitted model. Residual on a fresh render of the fit at {s["target_spp"]} spp
with a new seed: relative RMSE ‖fit − target‖₂ / ‖target‖₂ and the worst region (largest relative luminance error of an
{s["res"] // BLOCKS}×{s["res"] // BLOCKS}-pixel block mean among blocks at least {100 * BLOCK_MIN:.0f} % as bright as the image's mean block). The noise floor
is the same number for the target against a second target with another seed. Cells: green at the floor, red at 5× the
floor and above.</p>"""
    ]
    for name, sc in summary["scenes"].items():
        models = list(sc["cells"].keys())
        parts.append(
            f"<div class=scene><h2>{e(name)}</h2><p class=small>Scene <code>{e(sc['file'])}</code>; images: "
            f"{e(', '.join(sc['images']))}; materials fitted: {e(', '.join(sc['materials']))}; "
            f"prb max_depth {sc['max_depth']}.</p>"
        )
        for what, title in (("relative_rmse", "Relative RMSE (%)"), ("worst_region", "Worst region (%)")):
            head = "".join(f"<th>{e(LABELS[m])}</th>" for m in models)
            rows = []
            for t in models:
                floor = sc["noise_floor"][t][what]
                tds = "".join(
                    f"<td style='background:{cell_colour(sc['cells'][t][m][what], floor)}'>"
                    f"<a href='{e(name)}/{e(sc['cells'][t][m]['fit_report'])}'>{100 * sc['cells'][t][m][what]:.2f}</a></td>"
                    for m in models
                )
                rows.append(f"<tr><td>{e(LABELS[t])}</td>{tds}<td>{100 * floor:.2f}</td></tr>")
            parts.append(
                f"<h3>{title}</h3><table><tr><th>target \\ fitted</th>{head}<th>noise floor</th></tr>"
                f"{''.join(rows)}</table>"
            )
        head = "".join(f"<th>{e(LABELS[m])}</th>" for m in models)
        rows = []
        for t in models:
            tds = "".join(
                f"<td class=small>{e(shape_text(m, sc['cells'][t][m]['fitted']))}"
                f"{' (bound)' if any(not k.endswith('reflectance.value') for k in sc['cells'][t][m]['at_bound']) else ''}</td>"
                for m in models
            )
            rows.append(f"<tr><td>{e(LABELS[t])}</td>{tds}</tr>")
        parts.append(
            f"<h3>Fitted shape parameters</h3><table><tr><th>target \\ fitted</th>{head}</tr>{''.join(rows)}</table>"
            f"<p class=small>(bound): a shape parameter ended at its clamp range's end. Every fitted value is in "
            f"<a href='mimicry.json'>mimicry.json</a>.</p>"
        )
        parts.append(f"<h3>Differences</h3><img src='{e(name)}/grid.png'>")
        for t in models:
            parts.append(
                f"<h3>Target {e(LABELS[t])}: target | fit | (fit − target) / target, ±{100 * s['diff_range']:.0f} %</h3>"
                "<div style='display:flex;flex-wrap:wrap;gap:12px'>"
            )
            for m in models:
                c = sc["cells"][t][m]
                parts.append(
                    f"<figure style='margin:0'><img class=px src='{e(name)}/{e(c['strip'])}'>"
                    f"<figcaption class=small>{e(LABELS[m])}: {100 * c['relative_rmse']:.2f} %, worst "
                    f"{100 * c['worst_region']:.2f} % (<a href='{e(name)}/{e(c['fit_report'])}'>fit</a>)"
                    f"</figcaption></figure>"
                )
            parts.append("</div>")
        parts.append("</div>")
    parts.append(
        f"<p class=small>Total time {summary['seconds']:.0f} s. <a href='mimicry.json'>mimicry.json</a> has every number."
        "</p></body></html>\n"
    )
    with open(os.path.join(out, "index.html"), "w") as f:
        f.write("\n".join(parts))


def markdown(summary):
    """The tables of every scene as Markdown (docs/experiments/mimicry.md's): relative RMSE and worst region in
    %, each row with its noise floor, and the fitted shape parameters."""
    lines = []
    for name, sc in summary["scenes"].items():
        models = list(sc["cells"])
        head = "| target \\ fitted | " + " | ".join(LABELS[m] for m in models) + " | noise floor |"
        rule = "|---" * (len(models) + 2) + "|"
        for what, title in (("relative_rmse", "relative RMSE, %"), ("worst_region", "worst region, %")):
            lines += [f"**{name}: {title}**", "", head, rule]
            for t in models:
                cells = []
                for m in models:
                    v, floor = sc["cells"][t][m][what], sc["noise_floor"][t][what]
                    text = f"{100 * v:.2f}"
                    cells.append(f"**{text}**" if v > 2 * floor else text)
                lines.append(f"| {LABELS[t]} | " + " | ".join(cells) + f" | {100 * sc['noise_floor'][t][what]:.2f} |")
            lines.append("")
        lines += [
            f"**{name}: fitted shape parameters**",
            "",
            head.replace(" noise floor |", ""),
            "|---" * (len(models) + 1) + "|",
        ]
        for t in models:
            lines.append(
                f"| {LABELS[t]} | "
                + " | ".join(shape_text(m, sc["cells"][t][m]["fitted"]) or "–" for m in models)
                + " |"
            )
        lines.append("")
    return "\n".join(lines)


def write_reports(out, summary):
    """index.html and mimicry.md."""
    write_html(out, summary)
    with open(os.path.join(out, "mimicry.md"), "w") as f:
        f.write(markdown(summary))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("-o", "--output", default="mimicry_out")
    ap.add_argument("--scenes", default="cornell,sphere")
    ap.add_argument("--models", default=",".join(MODELS), help="comma-separated subset of " + ", ".join(MODELS))
    ap.add_argument("--res", type=int, default=32)
    ap.add_argument("--iterations", type=int, default=24)
    ap.add_argument("--lr", type=float, default=0.08)
    ap.add_argument("--lr-final", type=float, default=0.002)
    ap.add_argument(
        "--rho-lr-factor",
        type=float,
        default=0.25,
        help="the reflectances' learning rate relative to the shape parameter's",
    )
    ap.add_argument("--spp", type=int, default=8, help="samples per pixel of each optimisation render")
    ap.add_argument("--target-spp", type=int, default=1024)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--diff-range", type=float, default=0.2, help="colour scale of the difference images (relative)")
    ap.add_argument(
        "--start",
        action="append",
        default=[],
        metavar="MODEL=VALUE",
        help="start fits of MODEL at this shape parameter instead of the study's value (repeatable)",
    )
    ap.add_argument("--targets", help="comma-separated rows (target models) to run; default: --models")
    ap.add_argument(
        "--collect",
        action="store_true",
        help="rebuild mimicry.json and the reports from the pair folders in -o (runs split with --targets)",
    )
    ap.add_argument(
        "--report-only",
        action="store_true",
        help="redraw the pictures and the page from the outputs of an earlier run in -o",
    )
    args = ap.parse_args(argv)
    args.models = args.models.split(",")
    args.targets = args.targets.split(",") if args.targets else list(args.models)
    for m in args.targets:
        if m not in MODELS:
            ap.error(f"--targets: unknown model {m!r} (one of {', '.join(MODELS)})")
    try:
        args.start = {m: float(v) for m, v in (x.split("=", 1) for x in args.start)}
    except ValueError:
        ap.error("--start: expected MODEL=NUMBER")
    for m in args.start:
        if m not in MODELS or not SHAPE[m]:
            ap.error(f"--start: {m!r} is not a model with a shape parameter")
    for m in args.models:
        if m not in MODELS:
            ap.error(f"--models: unknown model {m!r} (one of {', '.join(MODELS)})")

    import mitsuba as mi

    mi.set_variant("llvm_ad_rgb")
    import matte_mitsuba  # noqa: F401  (registers the plugins)

    out = os.path.abspath(args.output)
    if args.report_only:
        with open(os.path.join(out, "mimicry.json")) as f:
            summary = json.load(f)
        for name, sc in summary["scenes"].items():
            rows = list(sc["cells"])
            columns = [m for m in MODELS if any(m in r for r in sc["cells"].values())]
            folder = os.path.join(out, name)
            targets = load_targets(folder, rows, len(sc["images"]))
            pictures(folder, rows, columns, targets, sc["cells"], summary["settings"]["diff_range"])
        write_reports(out, summary)
        print(os.path.join(out, "index.html"))
        return 0
    os.makedirs(out, exist_ok=True)
    specs = scene_specs(out, args.res)
    started = time.time()
    summary = {
        "settings": {k: v for k, v in vars(args).items() if k not in ("output", "collect", "report_only")},
        "scenes": {},
    }
    for name in args.scenes.split(","):
        if name not in specs:
            ap.error(f"--scenes: unknown scene {name!r} (one of {', '.join(specs)})")
        run = collect_scene if args.collect else run_scene
        summary["scenes"][name] = run(mi, name, specs[name], out, args)
    if args.collect:
        summary["collected"] = True
    summary["seconds"] = time.time() - started
    with open(os.path.join(out, "mimicry.json"), "w") as f:
        json.dump(summary, f, indent=1)
    write_reports(out, summary)
    print(os.path.join(out, "index.html"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
