"""The study's Cornell box (mitsuba_scenes/study/cornell.xml) with the tabulated ground-truth
BRDFs beside the analytic models (docs/microgeometry.md#back-to-the-papers-question): every
configuration rendered by `matte render` in K passes with the same K seeds, the image-mean
luminance (Rec. 709) and the luminance of the region below the green box as ratios to Lambert,
paired per seed, with 99 % Student-t intervals over the passes. Writes OUT/cornell_ground_truth.json
and OUT/cornell_ground_truth.png (tone-mapped images side by side).

    .venv/bin/python validation/experiments/microgeometry_cornell.py OUT [--passes 8] [--spp 32] [--res 128]
"""

import argparse
import json
import re
import subprocess
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import mitsuba as mi  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "mitsuba_scenes" / "study" / "cornell.xml"
MATTE = Path(__import__("os").environ.get("MATTE", ROOT / "target" / "release" / "matte"))
TRUTH = ROOT / "python" / "matte_mitsuba" / "ground_truth"
# t quantile 0.995 for K - 1 degrees of freedom.
T995 = {3: 5.841, 4: 4.604, 5: 4.032, 7: 3.499, 9: 3.250, 11: 3.106, 15: 2.947}

# (key, label, bsdf type, properties): the study's defaults (σ = m = r = 0.3), full Oren–Nayar,
# EON at the r that fits V-cavities of σ = 0.3 best (docs/microgeometry.md#eons-roughness), and
# the two simulated surfaces of roughness 0.3 as tables.
CONFIGS = [
    ("lambert", "Lambert", "lambert", []),
    ("oren_nayar", "Oren–Nayar qualitative σ=0.3", "oren_nayar", []),
    ("oren_nayar_full", "Oren–Nayar full σ=0.3", "oren_nayar", [("string", "model", "full")]),
    ("eon", "EON r=0.3 (study)", "eon", []),
    ("eon_fitted", "EON r=0.13 (fit to V-cavities)", "eon", [("float", "roughness", "0.13")]),
    ("ginneken", "van Ginneken m=0.3", "ginneken", []),
    (
        "truth_v_cavities",
        "ground truth: V-cavities σ=0.3",
        "tabulated_brdf",
        [("string", "filename", str(TRUTH / "v_cavities_sigma0.3.json"))],
    ),
    (
        "truth_height_field",
        "ground truth: height field m=0.3",
        "tabulated_brdf",
        [("string", "filename", str(TRUTH / "height_field_m0.3.json"))],
    ),
]


def derived_scene(out, key, bsdf, props):
    props_xml = "".join(f'<{t} name="{n}" value="{v}"/>' for t, n, v in props)
    text = re.sub(
        r'<bsdf type="\$bsdf" id="(\w+)">',
        lambda m: f'<bsdf type="{bsdf}" id="{m.group(1)}">{props_xml}',
        SCENE.read_text(),
    )
    path = out / f"cornell_{key}.xml"
    path.write_text(text.replace('value="assets/', f'value="{SCENE.parent}/assets/'))
    return path


def luminance(exr):
    img = np.array(mi.Bitmap(str(exr)), dtype=np.float64)[..., :3]
    return img @ np.array([0.212671, 0.715160, 0.072169]), img


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--spp", type=int, default=32)
    ap.add_argument("--res", type=int, default=128)
    a = ap.parse_args()
    mi.set_variant("scalar_rgb")
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    region = next(
        r
        for r in json.loads((SCENE.with_suffix(".regions.json")).read_text())["regions"]
        if r["name"].startswith("floor below")
    )["rect"]
    x0, y0, x1, y1 = (int(round(v * a.res)) for v in region)
    means, regions, images = {}, {}, {}
    for key, _, bsdf, props in CONFIGS:
        scene = derived_scene(out, key, bsdf, props)
        means[key], regions[key], acc = [], [], 0
        for k in range(a.passes):
            exr = out / f"{key}_{k}.exr"
            subprocess.run(
                [
                    str(MATTE),
                    "render",
                    str(scene),
                    "-q",
                    "--seed",
                    str(k),
                    "--spp",
                    str(a.spp),
                    "-D",
                    f"res={a.res}",
                    "-o",
                    str(exr),
                ],
                check=True,
                stdout=subprocess.DEVNULL,
            )
            lum, img = luminance(exr)
            means[key].append(lum.mean())
            regions[key].append(lum[y0:y1, x0:x1].mean())
            acc = acc + img
            exr.unlink()
        images[key] = acc / a.passes
        print(key, np.mean(means[key]))

    def ratio(values, key):
        r = np.array(values[key]) / np.array(values["lambert"])
        hw = T995.get(a.passes - 1, 2.576) * r.std(ddof=1) / np.sqrt(a.passes) if a.passes > 1 else float("nan")
        return {"ratio": float(r.mean()), "half_width": float(hw)}

    result = {"passes": a.passes, "spp": a.spp, "res": a.res, "configurations": []}
    for key, label, _bsdf, _props in CONFIGS:
        result["configurations"].append(
            {
                "key": key,
                "label": label,
                "image_mean_ratio": ratio(means, key),
                "floor_below_green_box_ratio": ratio(regions, key),
            }
        )
    (out / "cornell_ground_truth.json").write_text(json.dumps(result, indent=2))
    fig, axes = plt.subplots(1, len(CONFIGS), figsize=(2.6 * len(CONFIGS), 3.2))
    for ax, (key, label, _, _), c in zip(axes, CONFIGS, result["configurations"]):
        ax.imshow(np.clip(images[key] / (1 + images[key]), 0, 1) ** (1 / 2.2), interpolation="nearest")
        ax.set_title(
            f"{label}\n{c['image_mean_ratio']['ratio']:.3f} ± {c['image_mean_ratio']['half_width']:.3f}", fontsize=7
        )
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(out / "cornell_ground_truth.png", dpi=110)
    for c in result["configurations"]:
        m, f = c["image_mean_ratio"], c["floor_below_green_box_ratio"]
        print(
            f"{c['label']:36s} image {m['ratio']:.4f} ± {m['half_width']:.4f}   floor {f['ratio']:.4f} ± {f['half_width']:.4f}"
        )


if __name__ == "__main__":
    main()
