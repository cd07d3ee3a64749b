"""For each rough model of the study, the slice of its BRDF where it differs most from the
simulated surface it describes (docs/microgeometry.md, docs/study.md#true-surfaces).

The model is evaluated with `matte brdf --pairs` at every node (θi, θo, Δφ) of its surface's
table (python/matte_mitsuba/ground_truth/), at the plugin's defaults (roughness 0.3, as in the study);
the table's f/ρ is interpolated linearly in ρ, as `tabulated_brdf` does. The node with the
largest |model − surface| / surface at θi, θo ≤ 80° (the range of docs/microgeometry.md's
comparison; the table's grazing nodes are noisy) picks the slice: f against θo in the plane of
that Δφ (negative θo: the opposite azimuth, Δφ + 180°), with the surface's 99 % intervals.
Writes OUT/truth_slice_<model>.png and OUT/truth_slices.json.

    .venv/bin/python validation/generators/truth_error_slices.py OUT [--reflectance 0.8]
"""

import argparse
import json
import os
import subprocess
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
MATTE = Path(os.environ.get("MATTE", ROOT / "target" / "release" / "matte"))
TRUTH = ROOT / "python" / "matte_mitsuba" / "ground_truth"

# (study.json key, label, plugin, parameters, table): the study's models with a surface.
MODELS = [
    ("oren_nayar_qualitative", "Oren–Nayar (qualitative)", "oren_nayar", [], "v_cavities_sigma0.3.json"),
    ("oren_nayar_full", "Oren–Nayar (full)", "oren_nayar", ["model=full"], "v_cavities_sigma0.3.json"),
    ("eon", "EON", "eon", [], "v_cavities_sigma0.3.json"),
    ("ginneken", "van Ginneken", "ginneken", [], "height_field_m0.3.json"),
]


def load_table(path, rho):
    """The table's f and 99 % half-width at reflectance rho, shape (θi, θo, Δφ)."""
    t = json.loads(path.read_text())
    th, ph, rs = (np.array(t[k]) for k in ("theta_deg", "delta_phi_deg", "reflectance"))
    shape = (len(rs), len(th), len(th), len(ph))
    f = np.array(t["f_over_reflectance"]).reshape(shape)
    hw = np.array(t["half_width_over_reflectance"]).reshape(shape)
    k = min(max(np.searchsorted(rs, rho) - 1, 0), len(rs) - 2)
    w = (rho - rs[k]) / (rs[k + 1] - rs[k])
    return th, ph, rho * ((1 - w) * f[k] + w * f[k + 1]), rho * ((1 - w) * hw[k] + w * hw[k + 1])


def direction(theta, phi):
    t, p = np.radians(theta), np.radians(phi)
    return np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)


def evaluate(bsdf, params, rho, wi, wo):
    """The model's f at direction pairs (arrays of unit vectors, local frame)."""
    lines = "\n".join(" ".join(f"{x:.9f}" for x in (*a, *b)) for a, b in zip(wi, wo))
    cmd = [str(MATTE), "brdf", "--bsdf", bsdf, "--reflectance", str(rho), "--pairs", "-"]
    for p in params:
        cmd += ["--param", p]
    out = subprocess.run(cmd, input=lines, capture_output=True, text=True, check=True).stdout
    return np.array(json.loads(out)["f"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--reflectance", type=float, default=0.8)
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    summary = {"reflectance": a.reflectance, "models": []}
    for key, label, bsdf, params, table in MODELS:
        th, ph, f_true, hw = load_table(TRUTH / table, a.reflectance)
        ti, to, pp = np.meshgrid(th, th, ph, indexing="ij")
        f_model = evaluate(
            bsdf, params, a.reflectance, direction(ti, 0.0).reshape(-1, 3), direction(to, pp).reshape(-1, 3)
        ).reshape(ti.shape)
        rel = (f_model - f_true) / f_true
        mask = (ti <= 80) & (to <= 80)
        i, o, p = np.unravel_index(np.argmax(np.where(mask, np.abs(rel), -1)), rel.shape)
        phi = ph[p]
        # The slice: θo on both sides of the normal, Δφ and Δφ + 180°.
        opposite = int(np.argmin(np.abs(ph - (180 - phi))))
        xs = np.concatenate([-th[::-1], th[1:]])
        truth = np.concatenate([f_true[i, ::-1, opposite], f_true[i, 1:, p]])
        err = np.concatenate([hw[i, ::-1, opposite], hw[i, 1:, p]])
        model = np.concatenate([f_model[i, ::-1, opposite], f_model[i, 1:, p]])
        fig, ax = plt.subplots(figsize=(5.2, 3.4))
        ax.errorbar(xs, truth, yerr=err, fmt="o", ms=3, color="k", label=f"surface ({table[:-5]})")
        ax.plot(xs, model, "-", color="C3", label=label)
        ax.axvline(th[o], color="0.7", lw=0.8, ls="--")
        ax.set_xlabel(f"θo (°); positive: Δφ = {phi:.0f}°, negative: Δφ = {ph[opposite]:.0f}°")
        ax.set_ylabel("f (1/sr)")
        ax.set_title(
            f"{label} against its surface, ρ = {a.reflectance}, θi = {th[i]:.0f}°\nlargest error "
            f"{100 * rel[i, o, p]:+.1f} % at θo = {th[o]:.0f}°, Δφ = {phi:.0f}°",
            fontsize=8,
        )
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(out / f"truth_slice_{key}.png", dpi=100)
        plt.close(fig)
        summary["models"].append(
            {
                "model": key,
                "table": table,
                "theta_i": float(th[i]),
                "theta_o": float(th[o]),
                "delta_phi": float(phi),
                "relative_error": float(rel[i, o, p]),
                "mean_abs_relative_error": float(np.abs(rel[mask]).mean()),
            }
        )
        print(
            f"{label:26s} largest {100 * rel[i, o, p]:+6.1f} % at θi {th[i]:.0f}°, θo {th[o]:.0f}°, "
            f"Δφ {phi:.0f}°; mean |error| {100 * np.abs(rel[mask]).mean():.1f} %"
        )
    (out / "truth_slices.json").write_text(json.dumps(summary, indent=2))


if __name__ == "__main__":
    main()
