#!/usr/bin/env python3
"""Writes conductor_ior_data.rs: the RGB complex index (eta, k) of every named conductor
`material` that Mitsuba 3.9.1 knows, exactly as its RGB variants compute them.

A `material` name resolves to the spectral tables `data/ior/<name>.eta.spd` and
`data/ior/<name>.k.spd` shipped in the wheel (`complex_ior_from_file` in
`include/mitsuba/render/ior.h`); in RGB mode they are integrated against the CIE 1931 curves
without D65 weighting (`spectrum_list_to_srgb(bounded=false, d65=false)`). Rather than
re-implementing that integration, this script asks the pinned Mitsuba for the result: it
loads a `conductor` with each material in `scalar_rgb` and reads `eta.value` / `k.value`
back (f32, printed with full precision). Run once with the pinned wheel:

    /work/main/.venv/bin/python rust/render/bsdf/generate_conductor_ior.py
"""

import os
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")

here = os.path.dirname(os.path.abspath(__file__))
ior_dir = os.path.join(os.path.dirname(mi.__file__), "data", "ior")
files = os.listdir(ior_dir)
names = sorted(
    {f[: -len(".eta.spd")] for f in files if f.endswith(".eta.spd")}
    & {f[: -len(".k.spd")] for f in files if f.endswith(".k.spd")}
)

rows = []
for name in names:
    params = mi.traverse(mi.load_dict({"type": "conductor", "material": name}))
    eta = [float(params["eta.value"][i]) for i in range(3)]
    k = [float(params["k.value"][i]) for i in range(3)]
    fmt = lambda v: "[" + ", ".join(repr(x) for x in v) + "]"
    rows.append(f'    ("{name}", {fmt(eta)}, {fmt(k)}),')

out = os.path.join(here, "conductor_ior_data.rs")
with open(out, "w") as f:
    f.write(
        "//! RGB (η, k) of Mitsuba 3.9.1's named conductors in `scalar_rgb`, written by\n"
        "//! `generate_conductor_ior.py` from the wheel's `data/ior/*.spd` tables. Do not edit.\n\n"
        "/// `(material, eta, k)`, sorted by name (byte order).\n"
        "#[rustfmt::skip]\n"
        "pub(super) const MATERIALS: &[(&str, [f32; 3], [f32; 3])] = &[\n" + "\n".join(rows) + "\n];\n"
    )
print(f"wrote {out}: {len(rows)} materials", file=sys.stderr)
