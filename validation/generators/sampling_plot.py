"""The lobe-level plot of docs/sampling.md: the variance of the sampling weight f·cos/pdf
(ρ = 1) against the incidence θi, per model and roughness, under each model's sampler (solid)
and under the cosine (dashed), from `matte bench --sampling`'s sampling.json.

    ./target/release/matte bench --sampling -o bench_out
    .venv/bin/python validation/generators/sampling_plot.py bench_out/sampling.json docs/sampling/lobe_variance.png
"""

import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src, dst):
    rows = json.load(open(src))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, roughness in zip(axes, (0.3, 1.0)):
        # Lambert's weight is constant (variance 0): not on a log axis.
        picked = [
            r
            for r in rows
            if (r["roughness"] == roughness or r["roughness"] == 0.0)
            and any(l["variance_cosine"] > 1e-6 * l["albedo"] ** 2 for l in r["lobe"])
        ]
        for k, r in enumerate(picked):
            colour = f"C{k % 10}"
            theta = [l["theta_i"] for l in r["lobe"]]
            floor = [1e-6 * l["albedo"] ** 2 for l in r["lobe"]]
            cosine = [max(l["variance_cosine"], f) for l, f in zip(r["lobe"], floor)]
            label = r["label"] if r["roughness"] else r["model"]
            if r["own_sampler"]:
                own = [max(l["variance"], f) for l, f in zip(r["lobe"], floor)]
                ax.plot(theta, own, "-o", color=colour, ms=3, label=f"{label}: own sampler")
                ax.plot(theta, cosine, "--", color=colour, label=f"{label}: cosine")
            else:
                ax.plot(theta, cosine, "--", color=colour, label=f"{label}: cosine")
        ax.set_yscale("log")
        ax.set_xlabel("θi (degrees)")
        ax.set_title(f"roughness {roughness} (Wolff has none; Lambert: 0)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("Var[f cos θo / pdf], ρ = 1")
    fig.suptitle("Variance of the sampling weight per incidence (exact, by quadrature)")
    fig.tight_layout()
    fig.savefig(dst, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
