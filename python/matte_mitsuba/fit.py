"""Inverse rendering with matte's models: ``python -m matte_mitsuba.fit`` (also ``matte fit``).

Given a scene, target images and the scene parameters to free, it optimises those parameters
with Mitsuba's ``prb`` integrator and ``mi.ad.Adam`` so that renders match the targets::

    python -m matte_mitsuba.fit scene.xml --target target.exr \\
        --param plane.bsdf.sigma.data --param plane.bsdf.reflectance.data -o fit_out

* **Configurations.** ``--config "light=back,view=front"`` (repeatable) loads the scene once
  per configuration with those ``-D``-style defines; the freed parameters are shared by all of
  them and the loss is the mean over configurations. One target per configuration, in order:
  ``--target FILE.exr`` (repeatable), or ``--target-scene TRUTH.xml``, rendered per
  configuration at ``--target-spp`` (then the truth is known: every freed key that the truth
  scene also has is compared, and a parameter-error plot is drawn).
* **Parameters** are Mitsuba ``SceneParameters`` keys (``python -m matte_mitsuba.fit scene.xml
  --list`` prints the differentiable ones): floats (``obj.bsdf.sigma``) or textures' data
  (``obj.bsdf.sigma.data``, ``obj.bsdf.reflectance.data``). ``--init KEY=VALUE`` sets a start
  value (a texture is filled with it). After every step the values are clamped to where the
  model registry lets a fit search the parameter the key names, for the matte type of its BSDF
  (``registry.fit_range``: each parameter's ``fit`` bounds in its Rust declaration; a
  reflectance in [0, 1], of any BSDF); ``--range KEY=LO,HI`` overrides.
* **Loss**: mean squared error per pixel and channel, averaged over configurations.
* **Learning rate**: ``--lr``, constant, or decaying geometrically to ``--lr-final`` at the last
  iteration (Adam's steps keep a size of about the learning rate while the gradients are
  noisy, so a decay lets the parameters settle instead of jittering around the optimum);
  ``--lr-factor KEY=F`` scales one key's (e.g. small reflectances next to a roughness).
* **Outputs** in ``-o``: ``fit.json`` (settings, loss and parameter-error history, fitted
  values), per freed texture its fitted EXR and PNG (and truth and |error| PNGs when known),
  ``loss.png``, ``param_error.png`` (when the truth is known), final render / target PNGs per
  configuration, and ``index.html`` tying them together.

Plots need matplotlib: ``pip install 'matte-mitsuba[fit]'`` installs it with the package.
"""

import argparse
import html
import json
import math
import os
import re
import sys
import time

from . import registry


class FitError(Exception):
    """Bad input: printed as one line ``matte fit: error: ...``."""


def parse_args(argv):
    p = argparse.ArgumentParser(prog="matte fit", description=__doc__.split("\n\n")[0])
    p.add_argument("scene", help="Mitsuba 3 XML scene (with matte's BSDFs) whose parameters are fitted")
    p.add_argument(
        "--param", action="append", default=[], metavar="KEY", help="SceneParameters key to free (repeatable)"
    )
    p.add_argument("--target", action="append", default=[], metavar="EXR", help="target image, one per configuration")
    p.add_argument("--target-scene", metavar="XML", help="render the targets from this scene (the truth is then known)")
    p.add_argument(
        "--config",
        action="append",
        default=[],
        metavar="NAME=V,...",
        help="a configuration: defines for the scene (and the target scene); repeatable",
    )
    p.add_argument(
        "--init", action="append", default=[], metavar="KEY=VALUE", help="start value of a freed key (a colour: R,G,B)"
    )
    p.add_argument("--range", action="append", default=[], metavar="KEY=LO,HI", help="clamp range of a freed key")
    p.add_argument("--iterations", type=int, default=200)
    p.add_argument("--lr", type=float, default=0.02, help="Adam's learning rate (default 0.02)")
    p.add_argument(
        "--lr-final",
        type=float,
        metavar="LR",
        help="learning rate of the last iteration: geometric decay from --lr (default: constant --lr)",
    )
    p.add_argument(
        "--lr-factor",
        action="append",
        default=[],
        metavar="KEY=F",
        help="this key's learning rate is F times the others' (repeatable)",
    )
    p.add_argument("--spp", type=int, default=16, help="samples per pixel of each optimisation render")
    p.add_argument("--target-spp", type=int, default=256, help="samples per pixel of target renders")
    p.add_argument("--max-depth", type=int, default=3, help="prb's max_depth (default 3: direct + one bounce)")
    p.add_argument("--variant", default="llvm_ad_rgb")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("-o", "--output", default="fit_out", help="output folder (default fit_out)")
    p.add_argument("--list", action="store_true", help="print the scene's differentiable keys and exit")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    return p.parse_args(argv)


def parse_defines(text):
    out = {}
    for item in filter(None, (s.strip() for s in text.split(","))):
        if "=" not in item:
            raise FitError(f"--config {text!r}: expected NAME=VALUE pairs separated by commas")
        k, v = item.split("=", 1)
        out[k.strip()] = v.strip()
    return out


def parse_pairs(items, what):
    out = {}
    for item in items:
        if "=" not in item:
            raise FitError(f"{what} {item!r}: expected KEY=VALUE")
        k, v = item.split("=", 1)
        out[k] = v
    return out


def matte_type(params, key):
    """The matte type of the BSDF the ``SceneParameters`` key belongs to (one of its own
    parameters, or the data of a texture it holds): the first object up the key's traversal
    hierarchy that is one of matte's BSDFs, whose description names its type; ``None`` when
    no matte BSDF holds the key."""
    node = params.properties[key][2]
    while node is not None:
        if node.class_name() == "MatteBSDF":
            found = re.search(r'type = "(\w+)"', str(node))
            return found.group(1) if found else None
        node = params.hierarchy.get(node, (None, 0))[0]
    return None


def range_for(key, overrides, kind):
    """The clamp range of the freed ``key``: ``--range``'s, else where the registry lets a fit
    search the parameter the key names (the last dotted component that is a numeric parameter
    of the matte type ``kind``, or ``reflectance``), else none."""
    if key in overrides:
        try:
            lo, hi = (float(x) for x in overrides[key].split(","))
        except ValueError:
            raise FitError(f"--range {key}={overrides[key]}: expected LO,HI") from None
        return lo, hi
    names = {"reflectance"} | ({p["name"] for p in registry.numeric_parameters(kind)} if kind else set())
    for part in reversed(key.split(".")):
        if part in names:
            return registry.fit_range(kind, part) if kind else registry.REFLECTANCE_FIT
    return (-math.inf, math.inf)


class ProgressBar:
    def __init__(self, total, quiet):
        self.total, self.quiet, self.start = total, quiet or not sys.stderr.isatty(), time.time()
        self.quiet_every = max(1, total // 10)

    def update(self, i, loss):
        done = i + 1
        if self.quiet:
            if done % self.quiet_every == 0 or done == self.total:
                print(f"fit: {done}/{self.total} loss {loss:.4e}", file=sys.stderr, flush=True)
            return
        width = 30
        filled = int(width * done / self.total)
        rate = (time.time() - self.start) / done
        eta = rate * (self.total - done)
        sys.stderr.write(
            f"\rfit [{'#' * filled}{'.' * (width - filled)}] {done}/{self.total} loss {loss:.4e} eta {eta:5.0f}s"
        )
        if done == self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def as_numpy(value):
    import numpy as np

    return np.array(value, dtype=np.float64)


def write_texture_png(path, data, vmin, vmax, title):
    """A freed texture as a PNG: a colormapped image with a colour bar (1 channel), else sRGB."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, ax = plt.subplots(figsize=(4, 3.4), dpi=100)
    if data.ndim == 3 and data.shape[2] >= 3:
        ax.imshow(np.clip(data[..., :3], 0, 1) ** (1 / 2.2), interpolation="nearest")
    else:
        im = ax.imshow(
            data.reshape(data.shape[0], data.shape[1]), cmap="viridis", vmin=vmin, vmax=vmax, interpolation="nearest"
        )
        fig.colorbar(im, ax=ax)
    ax.set_title(title, fontsize=9)
    ax.set_axis_off()
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def write_image_png(path, img):
    """A linear RGB image as an sRGB PNG (Mitsuba's own conversion)."""
    import mitsuba as mi

    mi.Bitmap(img).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, True).write(path)


def plot_curves(path, series, ylabel, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 3.6), dpi=100)
    for label, ys in series.items():
        ax.plot(range(len(ys)), ys, label=label)
    ax.set_yscale("log")
    ax.set_xlabel("iteration")
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    if len(series) > 1:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def learning_rate(args, it):
    """Adam's learning rate at iteration `it`: --lr, decaying geometrically to --lr-final."""
    if args.lr_final is None or args.iterations < 2:
        return args.lr
    return args.lr * (args.lr_final / args.lr) ** (it / (args.iterations - 1))


def safe_name(key):
    return key.replace("/", "_")


def fit(args):
    import drjit as dr
    import mitsuba as mi
    import numpy as np

    mi.set_variant(args.variant)
    from . import register

    register()

    if not os.path.exists(args.scene):
        raise FitError(f"{args.scene}: no such scene file")
    configs = [parse_defines(c) for c in args.config] or [{}]

    def load(path, defines):
        try:
            return mi.load_file(path, **defines)
        except Exception as e:  # Mitsuba's own message names the file and the problem
            raise FitError(f"{path}: {str(e).splitlines()[0] if str(e) else type(e).__name__}") from e

    scenes = [load(args.scene, d) for d in configs]
    params = [mi.traverse(s) for s in scenes]
    if args.list:
        for k in params[0].keys():
            if params[0].flags(k) & mi.ParamFlags.NonDifferentiable.value:
                continue
            print(k)
        return 0
    if not args.param:
        raise FitError("give at least one --param KEY (--list prints the differentiable keys)")
    for k in args.param:
        if k not in params[0]:
            near = [x for x in params[0].keys() if x.split(".")[0] == k.split(".")[0]][:8]
            raise FitError(
                f"--param {k}: not a parameter of {args.scene}"
                + (f" (that object has: {', '.join(near)})" if near else "")
            )

    # Every render (targets, fit, final) uses the same integrator: prb, --max-depth.
    integrator = mi.load_dict({"type": "prb", "max_depth": args.max_depth})
    # Targets.
    truth = {}
    if args.target_scene and args.target:
        raise FitError("give either --target or --target-scene, not both")
    if args.target_scene:
        if not os.path.exists(args.target_scene):
            raise FitError(f"{args.target_scene}: no such scene file")
        targets = []
        for d in configs:
            ts = load(args.target_scene, d)
            targets.append(mi.render(ts, integrator=integrator, spp=args.target_spp, seed=10_000 + args.seed))
            tp = mi.traverse(ts)
            for k in args.param:
                if k in tp and k not in truth:
                    truth[k] = as_numpy(tp[k])
    else:
        if len(args.target) != len(configs):
            raise FitError(f"{len(configs)} configuration(s) need as many --target images, got {len(args.target)}")
        targets = []
        for path, s in zip(args.target, scenes):
            if not os.path.exists(path):
                raise FitError(f"{path}: no such target image")
            t = mi.TensorXf(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, False))
            film = s.sensors()[0].film().crop_size()
            if t.shape[0] != film[1] or t.shape[1] != film[0]:
                raise FitError(f"{path}: {t.shape[1]}x{t.shape[0]} pixels, but the scene's film is {film[0]}x{film[1]}")
            targets.append(t)

    inits = parse_pairs(args.init, "--init")
    ranges_over = parse_pairs(args.range, "--range")
    ranges = {k: range_for(k, ranges_over, matte_type(params[0], k)) for k in args.param}

    if not (args.lr > 0 and math.isfinite(args.lr)):
        raise FitError(f"--lr {args.lr}: must be a positive number")
    if args.lr_final is not None and not (args.lr_final > 0 and math.isfinite(args.lr_final)):
        raise FitError(f"--lr-final {args.lr_final}: must be a positive number")
    opt = mi.ad.Adam(lr=args.lr)
    for k in args.param:
        v = params[0][k]
        if k in inits:
            try:
                xs = [float(x) for x in inits[k].split(",")]
            except ValueError:
                raise FitError(f"--init {k}={inits[k]}: not a number (or R,G,B for a colour)") from None
            if len(xs) == 1:
                v = dr.full(type(v), xs[0], dr.shape(v)) if isinstance(v, mi.TensorXf) else type(v)(xs[0])
            elif len(xs) == 3 and not isinstance(v, mi.TensorXf) and dr.size_v(v) == 3:
                v = type(v)(*xs)
            else:
                raise FitError(f"--init {k}={inits[k]}: {len(xs)} values for a parameter of another size")
        opt[k] = v
    for k in inits:
        if k not in args.param:
            raise FitError(f"--init {k}: not one of the freed --param keys")
    lr_factors = {}
    for k, f in parse_pairs(args.lr_factor, "--lr-factor").items():
        if k not in args.param:
            raise FitError(f"--lr-factor {k}: not one of the freed --param keys")
        try:
            lr_factors[k] = float(f)
        except ValueError:
            raise FitError(f"--lr-factor {k}={f}: not a number") from None
        if not (lr_factors[k] > 0 and math.isfinite(lr_factors[k])):
            raise FitError(f"--lr-factor {k}={f}: must be a positive number")

    def clamp_and_share():
        for k in args.param:
            lo, hi = ranges[k]
            opt[k] = dr.clip(opt[k], lo, hi)
        for p in params:
            p.update(opt)

    clamp_and_share()
    os.makedirs(args.output, exist_ok=True)
    history = {"loss": [], "param_error": {k: [] for k in truth}}

    def param_errors():
        for k in truth:
            cur = as_numpy(opt[k])
            t = truth[k]
            if cur.size == t.size:
                history["param_error"][k].append(float(np.mean(np.abs(cur.ravel() - t.ravel()))))

    bar = ProgressBar(args.iterations, args.quiet)
    started = time.time()
    param_errors()
    for it in range(args.iterations):
        lr = learning_rate(args, it)
        opt.set_learning_rate(lr)
        if lr_factors:
            opt.set_learning_rate({k: lr * f for k, f in lr_factors.items()})
        total = 0.0
        for c, (scene, p, target) in enumerate(zip(scenes, params, targets)):
            img = mi.render(scene, p, integrator=integrator, spp=args.spp, seed=args.seed + it * len(scenes) + c)
            loss = dr.mean(dr.square(img - target), axis=None) / len(scenes)
            dr.backward(loss)
            total += float(loss.array[0]) if hasattr(loss, "array") else float(loss)
        # Every configuration's scene holds the optimiser's own variables (update(opt)), so
        # the backward passes above accumulated the total gradient on them.
        opt.step()
        clamp_and_share()
        history["loss"].append(total)
        param_errors()
        bar.update(it, total)
    history["seconds"] = time.time() - started
    write_outputs(args, configs, scenes, params, targets, truth, history, opt, ranges, integrator)
    return 0


def write_outputs(args, configs, scenes, params, targets, truth, history, opt, ranges, integrator):
    import mitsuba as mi
    import numpy as np

    out = args.output
    fitted = {}
    figures = []
    for k in args.param:
        v = as_numpy(opt[k])
        lo, hi = ranges[k]
        if isinstance(opt[k], mi.TensorXf):  # a texture's data: EXR + PNG (+ truth and error); a colour is a value
            name = safe_name(k)
            mi.Bitmap(mi.TensorXf(np.asarray(v, dtype=np.float32))).write(os.path.join(out, f"{name}.exr"))
            vmin = float(v.min()) if not math.isfinite(lo) else lo
            vmax = float(v.max()) if not math.isfinite(hi) else hi
            if k in truth and v.shape[-1] == 1:
                vmin, vmax = min(vmin, float(truth[k].min())), max(vmax, float(truth[k].max()))
            write_texture_png(os.path.join(out, f"{name}.png"), v, vmin, vmax, f"fitted {k}")
            entry = {
                "file": f"{name}.exr",
                "shape": list(v.shape),
                "mean": float(v.mean()),
                "min": float(v.min()),
                "max": float(v.max()),
            }
            figs = [(f"{name}.png", f"fitted {k}")]
            if k in truth and truth[k].shape == v.shape:
                t = truth[k]
                write_texture_png(os.path.join(out, f"{name}_truth.png"), t, vmin, vmax, f"truth {k}")
                err = np.abs(v - t)
                write_texture_png(
                    os.path.join(out, f"{name}_error.png"), err, 0.0, float(err.max()) or 1.0, f"|fitted - truth| {k}"
                )
                entry["mean_abs_error"] = float(err.mean())
                entry["max_abs_error"] = float(err.max())
                figs += [(f"{name}_truth.png", f"truth {k}"), (f"{name}_error.png", f"|error| {k}")]
            figures.append((k, figs))
            fitted[k] = entry
        else:
            entry = {"value": v.ravel().tolist()}
            if k in truth:
                entry["truth"] = truth[k].ravel().tolist()
                entry["abs_error"] = np.abs(v.ravel() - truth[k].ravel()).tolist()
            fitted[k] = entry

    renders = []
    for c, (scene, p, target) in enumerate(zip(scenes, params, targets)):
        img = mi.render(scene, p, integrator=integrator, spp=max(args.spp, 64), seed=99_999 + c)
        write_image_png(os.path.join(out, f"render_{c}.png"), img)
        write_image_png(os.path.join(out, f"target_{c}.png"), target)
        rmse = float(np.sqrt(np.mean((as_numpy(img) - as_numpy(target)) ** 2)))
        renders.append({"config": configs[c], "render": f"render_{c}.png", "target": f"target_{c}.png", "rmse": rmse})

    plot_curves(
        os.path.join(out, "loss.png"),
        {"loss": history["loss"]},
        "mean squared error",
        "loss (mean over configurations)",
    )
    if history["param_error"]:
        plot_curves(
            os.path.join(out, "param_error.png"), history["param_error"], "mean |fitted - truth|", "parameter error"
        )

    summary = {
        "scene": os.path.abspath(args.scene),
        "target_scene": os.path.abspath(args.target_scene) if args.target_scene else None,
        "targets": [os.path.abspath(t) for t in args.target],
        "configs": configs,
        "params": args.param,
        "ranges": {k: list(v) for k, v in ranges.items()},
        "settings": {
            "iterations": args.iterations,
            "lr": args.lr,
            "lr_final": args.lr_final,
            "lr_factors": parse_pairs(args.lr_factor, "--lr-factor"),
            "spp": args.spp,
            "target_spp": args.target_spp,
            "max_depth": args.max_depth,
            "variant": args.variant,
            "seed": args.seed,
        },
        "seconds": history.get("seconds"),
        "loss": history["loss"],
        "param_error": history["param_error"],
        "fitted": fitted,
        "renders": renders,
    }
    with open(os.path.join(out, "fit.json"), "w") as f:
        json.dump(summary, f, indent=1)
    write_html(out, summary, figures)


def write_html(out, s, figures):
    e = html.escape
    rows = []
    for k, v in s["fitted"].items():
        if "value" in v:
            val = ", ".join(f"{x:.5g}" for x in v["value"])
            err = ", ".join(f"{x:.3g}" for x in v.get("abs_error", [])) or "–"
            tru = ", ".join(f"{x:.5g}" for x in v.get("truth", [])) or "–"
        else:
            val = f"texture {v['shape']}, mean {v['mean']:.4g}, range [{v['min']:.4g}, {v['max']:.4g}]"
            tru = "known" if "mean_abs_error" in v else "–"
            err = f"mean {v['mean_abs_error']:.4g}, max {v['max_abs_error']:.4g}" if "mean_abs_error" in v else "–"
        rows.append(f"<tr><td><code>{e(k)}</code></td><td>{e(val)}</td><td>{e(tru)}</td><td>{e(err)}</td></tr>")
    figs = "".join(
        f"<h3><code>{e(k)}</code></h3><div class=row>"
        + "".join(f"<figure><img src='{e(f)}'><figcaption>{e(c)}</figcaption></figure>" for f, c in fl)
        + "</div>"
        for k, fl in figures
    )
    renders = "".join(
        f"<div class=row><figure><img class=px src='{e(r['target'])}'><figcaption>target, config {e(str(r['config']))}</figcaption></figure>"
        f"<figure><img class=px src='{e(r['render'])}'><figcaption>fitted render, RMSE {r['rmse']:.4g}</figcaption></figure></div>"
        for r in s["renders"]
    )
    curves = "<img src='loss.png'>" + ("<img src='param_error.png'>" if s["param_error"] else "")
    final = s["loss"][-1] if s["loss"] else float("nan")
    lr_final = s["settings"].get("lr_final")
    lr_decay = f" decaying to {lr_final}" if lr_final is not None else ""
    page = f"""<!doctype html><meta charset=utf-8><title>matte fit</title>
<style>body{{font:14px sans-serif;margin:2em;max-width:1100px}}td,th{{border:1px solid #ccc;padding:4px 8px}}
table{{border-collapse:collapse}}.row{{display:flex;gap:1em;flex-wrap:wrap}}img.px{{width:256px;image-rendering:pixelated}}
figure{{margin:0}}</style>
<h1>matte fit</h1>
<p>Scene <code>{e(s["scene"])}</code>; targets {e(s["target_scene"] or ", ".join(s["targets"]))};
{len(s["configs"])} configuration(s); {s["settings"]["iterations"]} iterations of Adam (lr {s["settings"]["lr"]}{lr_decay}),
prb max_depth {s["settings"]["max_depth"]}, {s["settings"]["spp"]} spp, variant {e(s["settings"]["variant"])}.
Final loss {final:.4e}.</p>
<h2>Parameters</h2><table><tr><th>key</th><th>fitted</th><th>truth</th><th>|fitted − truth|</th></tr>{"".join(rows)}</table>
<h2>Convergence</h2>{curves}
<h2>Fitted textures</h2>{figs or "<p>none</p>"}
<h2>Renders</h2>{renders}
<p><a href='fit.json'>fit.json</a> has every number.</p>
"""
    with open(os.path.join(out, "index.html"), "w") as f:
        f.write(page)


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        if not args.list:
            try:
                import matplotlib  # noqa: F401  (the plots; checked before the first render)
            except ImportError as e:
                raise FitError(
                    "the fit's plots need matplotlib, which this Python lacks: "
                    "pip install 'matte-mitsuba[fit]' (or pip install matplotlib)"
                ) from e
        code = fit(args)
    except FitError as e:
        print(f"matte fit: error: {e}", file=sys.stderr)
        return 2
    if not args.list:
        print(os.path.join(args.output, "index.html"))
    return code


if __name__ == "__main__":
    sys.exit(main())
