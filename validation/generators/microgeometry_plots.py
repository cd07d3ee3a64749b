"""Slices of `matte microgeometry` comparisons as PNGs: per incidence angle, the in-plane slice
(Δφ = 0 on the left of the axis, Δφ = 180° on the right) and the cross-plane slice (Δφ = 90°);
the simulated surface with its 99 % intervals (all bounces, and the first bounce only) beside
each model. Reads the JSON `matte microgeometry` prints; draws only (no numbers computed here).

    .venv/bin/python validation/generators/microgeometry_plots.py OUT_DIR COMPARISON.json [...]
"""

import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def slice_points(points, theta_i, phis):
    """(signed θo, point) for the given Δφ values: Δφ = 0 negative, the others positive."""
    out = []
    for p in points:
        if p["theta_i"] == theta_i and p["delta_phi"] in phis:
            x = -p["theta_o"] if (p["delta_phi"] == 0 and len(phis) > 1) else p["theta_o"]
            if x == 0 and p["delta_phi"] != phis[0]:
                continue
            out.append((x, p))
    return sorted(out, key=lambda t: t[0])


def plot(comparison, out_dir):
    points, models = comparison["points"], comparison["models"]
    thetas = sorted({p["theta_i"] for p in points})
    tag = f"{comparison['surface']}_r{comparison['roughness']:g}_rho{comparison['reflectance']:g}"
    fig, axes = plt.subplots(2, len(thetas), figsize=(4.2 * len(thetas), 7.5), squeeze=False)
    for col, ti in enumerate(thetas):
        for row, (phis, name) in enumerate([((0.0, 180.0), "in-plane"), ((90.0,), "cross-plane")]):
            ax = axes[row][col]
            pts = slice_points(points, ti, phis)
            xs = [x for x, _ in pts]
            for key, label, style in [
                ("simulated", "surface, all bounces", "o"),
                ("single_bounce", "surface, first bounce", "s"),
            ]:
                ax.errorbar(
                    xs,
                    [p[key]["mean"] for _, p in pts],
                    yerr=[p[key]["half_width"] for _, p in pts],
                    fmt=style,
                    ms=3.5,
                    capsize=2,
                    label=label,
                    color="black" if key == "simulated" else "grey",
                )
            for k, m in enumerate(models):
                ax.plot(xs, [p["model"][k] for _, p in pts], "-", lw=1.4, label=m)
            ax.set_title(f"θi = {ti:g}°, {name}")
            ax.set_xlabel("θo (°), negative: source side" if row == 0 else "θo (°)")
            ax.set_ylabel("f (1/sr)")
            ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=8)
    surface = "V-cavities σ" if comparison["surface"] == "v_cavities" else "Gaussian height field m"
    fig.suptitle(
        f"{surface} = {comparison['roughness']:g}, ρ = {comparison['reflectance']:g}: "
        f"simulated surface (99 % intervals) and models"
    )
    fig.tight_layout()
    path = Path(out_dir) / f"slices_{tag}.png"
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return path


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    for f in sys.argv[2:]:
        print(plot(json.loads(Path(f).read_text()), out))


if __name__ == "__main__":
    main()
