#!/usr/bin/env python3
"""Mitsuba 3.9.1's own render test suite, applied to `matte render`.

Usage:
    python validation/mitsuba_testsuite.py MITSUBA_DATA [--matte target/release/matte]
        [--only SUBSTRING] [--out DIR] [--timeout SECONDS] [--json FILE]

MITSUBA_DATA is a checkout (or export) of `mitsuba-renderer/mitsuba-data` with
`tests/scenes/` and `common/`. Nothing is downloaded.

For every surface scene `tests/scenes/*/*.xml` (the folders `participating_media`,
`various_shapes` and `volprim_rf_basic` are left out), this does what
`src/render/tests/test_renders.py` (Mitsuba v3.9.1) does for the `scalar_rgb` variant:

* the reference is `refs/<stem without the last _suffix>_ref_rgb.exr` and its per-pixel
  sample variance `..._ref_rgb_var.exr`;
* spp = 2·10^6 // pixel count; the scene is loaded with the parameters `spp` and
  `integrator` (= the file name's last `_suffix`) and rendered with seed 0. The file is
  used unmodified: a parameter is passed with `-D` only where the scene declares it with
  `<default name=...>` (Mitsuba's `load_file(..., spp=, integrator=)` sets the same ones);
* the image, the reference and the variance are converted from linear sRGB to XYZ
  (`mi.Bitmap.convert`, as the test does);
* per pixel and channel z = |mean − ref| · sqrt(spp / max(var_ref, 1e-4)), two-sided
  p = 2·(1 − Φ(z)); α = 1 − 0.99^(1/pixel count) (Šidák); the scene passes when at least
  99.75 % of the pixel-channels have p > α.

Printed per scene: rendered or refused (with matte's error), the accepted percentage, the
pass/fail decision, and the ratio of the image mean to the reference mean in Y. Nothing is
tuned per scene. Needs numpy and the `mitsuba` wheel (for EXR reading and the colour
conversion), e.g. the project's `.venv`.
"""

import argparse
import glob
import json
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

EXCLUDED_FOLDERS = ("participating_media", "various_shapes", "volprim_rf_basic")


def load_xyz(mi, fname):
    """An RGB EXR as an XYZ float32 array (H, W, 3), as `read_rgb_bmp_to_xyz` does."""
    bmp = mi.Bitmap(fname).convert(mi.Bitmap.PixelFormat.XYZ, mi.Struct.Type.Float32, False)
    img = np.array(bmp, copy=True)
    if img.ndim == 2:
        img = img[..., np.newaxis]
    return img


def p_values(mean, spp, ref, ref_var):
    """Mitsuba's `z_test`: two-sided p-value of the per-pixel-channel z statistic."""
    z = np.abs(mean - ref) * np.sqrt(spp / np.maximum(ref_var, 1e-4))
    erfc = np.vectorize(math.erfc, otypes=[np.float64])
    return erfc(z.astype(np.float64) / math.sqrt(2.0))


def ref_names(scene):
    stem = os.path.splitext(os.path.basename(scene))[0].rsplit("_", 1)[0]
    ref = os.path.join(os.path.dirname(scene), "refs", stem + "_ref_rgb.exr")
    return ref, ref.replace(".exr", "_var.exr")


def declared_defaults(scene):
    with open(scene, encoding="utf-8") as f:
        text = f.read()
    return set(re.findall(r'<default\s+name="([^"]+)"', text))


def list_scenes(data):
    scenes = sorted(glob.glob(os.path.join(data, "tests", "scenes", "*", "*.xml")))
    return [s for s in scenes if os.path.basename(os.path.dirname(s)) not in EXCLUDED_FOLDERS]


def run_scene(mi, matte, scene, out_dir, timeout):
    name = os.path.relpath(scene, os.path.dirname(os.path.dirname(scene)))
    row = {"scene": name}
    ref_f, var_f = ref_names(scene)
    if not (os.path.exists(ref_f) and os.path.exists(var_f)):
        row.update(status="no reference", error=f"missing {ref_f} or {var_f}")
        return row
    ref = load_xyz(mi, ref_f)
    ref_var = load_xyz(mi, var_f)
    pixel_count = ref.shape[0] * ref.shape[1]
    spp = int(2e6) // pixel_count
    integrator = os.path.splitext(os.path.basename(scene))[0].rsplit("_", 1)[-1]
    defaults = declared_defaults(scene)
    out = os.path.join(out_dir, name.replace(os.sep, "__").replace(".xml", ".exr"))
    cmd = [matte, "render", os.path.basename(scene), "-o", out, "--spp", str(spp), "--seed", "0", "--quiet"]
    if "spp" in defaults:
        cmd += ["-D", f"spp={spp}"]
    if "integrator" in defaults:
        cmd += ["-D", f"integrator={integrator}"]
    row.update(spp=spp, pixels=pixel_count)
    try:
        proc = subprocess.run(cmd, cwd=os.path.dirname(scene), capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        row.update(status="refused", error=f"timed out after {timeout} s")
        return row
    if proc.returncode != 0:
        err = proc.stderr.strip().splitlines()
        row.update(status="refused", error=err[-1] if err else f"exit status {proc.returncode}")
        return row
    try:
        report = json.loads(proc.stdout)
        row["render_seconds"] = report.get("render_seconds")
    except json.JSONDecodeError:
        pass
    img = load_xyz(mi, out)
    if img.shape != ref.shape:
        row.update(
            status="rendered", error=f"image shape {img.shape} != reference {ref.shape}", accepted=0.0, passed=False
        )
        return row
    p = p_values(img, spp, ref, ref_var)
    alpha = 1.0 - (1.0 - 0.01) ** (1.0 / pixel_count)
    accepted = np.count_nonzero(p > alpha) / 3
    ref_y = float(np.mean(ref[..., 1]))
    row.update(
        status="rendered",
        accepted=100.0 * accepted / pixel_count,
        passed=bool(accepted >= 0.9975 * pixel_count),
        mean_ratio=float(np.mean(img[..., 1])) / ref_y if ref_y != 0 else float("nan"),
        alpha=alpha,
    )
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("data", help="mitsuba-data folder (with tests/scenes and common)")
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap.add_argument("--matte", default=os.path.join(here, "target", "release", "matte"))
    ap.add_argument("--only", default=None, help="only scenes whose path contains this")
    ap.add_argument("--out", default=None, help="folder for the rendered EXRs (default: a temp dir)")
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--json", default=None, help="write the rows as JSON here")
    ap.add_argument("--markdown", default=None, help="write the table as Markdown here")
    args = ap.parse_args()

    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    scenes = list_scenes(args.data)
    if args.only:
        scenes = [s for s in scenes if args.only in s]
    if not scenes:
        sys.exit(f"no scenes under {args.data}/tests/scenes")
    out_dir = args.out or tempfile.mkdtemp(prefix="matte_testsuite_")
    os.makedirs(out_dir, exist_ok=True)
    matte = os.path.abspath(args.matte)
    rows = []
    print(f"{'scene':58} {'status':9} {'accepted %':>10} {'pass':>5} {'mean ratio (Y)':>14}")
    for scene in scenes:
        row = run_scene(mi, matte, scene, out_dir, args.timeout)
        rows.append(row)
        acc = f"{row['accepted']:.2f}" if "accepted" in row else "-"
        ok = ("yes" if row["passed"] else "no") if "passed" in row else "-"
        ratio = f"{row['mean_ratio']:.4f}" if "mean_ratio" in row else "-"
        print(f"{row['scene']:58} {row['status']:9} {acc:>10} {ok:>5} {ratio:>14}", flush=True)
        if row.get("error"):
            print(f"    {row['error']}", flush=True)
    rendered = [r for r in rows if r["status"] == "rendered"]
    passed = [r for r in rendered if r.get("passed")]
    print(f"\n{len(rows)} scenes: {len(rendered)} rendered, {len(passed)} passed Mitsuba's criterion")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(rows, f, indent=1)
    if args.markdown:
        with open(args.markdown, "w", encoding="utf-8") as f:
            f.write(markdown(rows))


def markdown(rows):
    """The table as Markdown: scene, rendered or refused (with the reason), accepted %, pass,
    mean ratio."""
    out = ["| scene | rendered | accepted % | pass | mean ratio (Y) |", "|---|---|---|---|---|"]
    for r in rows:
        status = (
            r["status"]
            if r["status"] != "refused"
            else "refused: " + r.get("error", "").replace("|", "\\|").replace("matte: error: ", "")
        )
        acc = f"{r['accepted']:.2f}" if "accepted" in r else "–"
        ok = ("yes" if r["passed"] else "**no**") if "passed" in r else "–"
        ratio = f"{r['mean_ratio']:.4f}" if "mean_ratio" in r else "–"
        out.append(f"| {r['scene']} | {status} | {acc} | {ok} | {ratio} |")
    rendered = [r for r in rows if r["status"] == "rendered"]
    out.append("")
    out.append(f"{len(rows)} scenes: {len(rendered)} rendered, {sum(1 for r in rendered if r.get('passed'))} passed.")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    main()
