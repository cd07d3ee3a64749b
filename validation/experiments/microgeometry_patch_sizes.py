"""Patch independence (docs/microgeometry.md#patch-independence): two `matte microgeometry
--surface height-field` comparisons of the same roughness and ρ with different patch sizes,
point by point. Prints how many grid points (f and albedo, all bounces and first bounce) agree
within the two pooled 99 % intervals combined, and the mean and largest relative difference.

    .venv/bin/python validation/experiments/microgeometry_patch_sizes.py SMALL.json LARGE.json
"""

import json
import math
import sys


def agreement(a, b, key):
    pairs = [(p[key], q[key]) for p, q in zip(a, b)]
    inside = sum(abs(x["mean"] - y["mean"]) <= math.hypot(x["half_width"], y["half_width"]) for x, y in pairs)
    rel = [abs(x["mean"] / y["mean"] - 1) for x, y in pairs]
    hw = [math.hypot(x["half_width"], y["half_width"]) / y["mean"] for x, y in pairs]
    return inside, len(pairs), sum(rel) / len(rel), max(rel), sum(hw) / len(hw)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    small, large = (json.load(open(f)) for f in sys.argv[1:])
    for c in (small, large):
        print(f"{c['cells'] // 8} T x {c['realisations']} realisations, {c['photons']} photons per θi")
    for part in ("points", "albedo"):
        for key in ("simulated", "single_bounce"):
            inside, n, mean, worst, hw = agreement(small[part], large[part], key)
            print(
                f"{part:7s} {key:14s}: {inside}/{n} within the intervals; relative difference mean "
                f"{100 * mean:.2f} %, largest {100 * worst:.2f} %; mean interval ±{100 * hw:.2f} %"
            )


if __name__ == "__main__":
    main()
