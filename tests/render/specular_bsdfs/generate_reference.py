#!/usr/bin/env python3
"""Writes tests/render/specular_bsdfs/mitsuba_reference.rs, the oracle of
`rough_conductor_matches_mitsuba_3_9_1` in tests/render/specular_bsdfs.rs: Mitsuba 3.9.1's own
`roughconductor` (`scalar_rgb`) evaluated at fixed directions. Run by hand with the venv's
Python from the repository root:

    .venv/bin/python tests/render/specular_bsdfs/generate_reference.py > tests/render/specular_bsdfs/mitsuba_reference.rs

Per configuration: normal incidence, one wo below the surface, then 18 random wi (a seeded
generator) each with a wo near its mirror direction (the lobe), as f32 unit vectors.
"""

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")

# Au: docs/renderer-semantics.md §10.
AU_ETA = [0.143036, 0.375307, 1.442045]
AU_K = [3.982997, 2.385556, 1.603359]
CONFIGS = [  # (name, distribution, alpha_u, alpha_v, specular_reflectance)
    ("BECKMANN_01_01", "beckmann", 0.1, 0.1, [1.0, 1.0, 1.0]),
    ("BECKMANN_05_05", "beckmann", 0.5, 0.5, [1.0, 1.0, 1.0]),
    ("BECKMANN_008_035", "beckmann", 0.08, 0.35, [0.9, 0.8, 0.7]),
    ("GGX_01_01", "ggx", 0.1, 0.1, [1.0, 1.0, 1.0]),
    ("GGX_05_05", "ggx", 0.5, 0.5, [1.0, 1.0, 1.0]),
    ("GGX_008_035", "ggx", 0.08, 0.35, [0.9, 0.8, 0.7]),
]
RUST_DIST = {"beckmann": "Beckmann", "ggx": "Ggx"}


def unit(v):
    v = np.asarray(v, dtype=np.float64)
    return (v / np.linalg.norm(v)).astype(np.float32)


def directions(rng):
    out = [(unit([0, 0, 1]), unit([0, 0, 1])), (unit([0.3, 0.2, 0.8]), unit([0.2, 0.8, -1.0]))]
    while len(out) < 20:
        wi = unit(rng.normal(size=3) * [1, 1, 0] + [0, 0, abs(rng.normal()) + 0.2])
        mirror = np.array([-wi[0], -wi[1], wi[2]])
        wo = unit(mirror + 0.35 * rng.normal(size=3))
        if wo[2] > 0.05:
            out.append((wi, wo))
    return out


def bsdf(dist, au, av, spec, visible):
    d = {
        "type": "roughconductor",
        "distribution": dist,
        "sample_visible": visible,
        "eta": {"type": "rgb", "value": AU_ETA},
        "k": {"type": "rgb", "value": AU_K},
    }
    if au == av:
        d["alpha"] = au
    else:
        d["alpha_u"], d["alpha_v"] = au, av
    if spec != [1.0, 1.0, 1.0]:
        d["specular_reflectance"] = {"type": "rgb", "value": spec}
    return mi.load_dict(d)


def f(x):
    return str(np.float32(x))


def main():
    rng = np.random.default_rng(20261204)
    print("//! Expected `eval`/`pdf` values of the real Mitsuba 3.9.1 `roughconductor` (PyPI wheel")
    print("//! `mitsuba==3.9.1`, `drjit==1.5.0`, variant `scalar_rgb`), written by")
    print("//! `tests/render/specular_bsdfs/generate_reference.py` (Au's eta/k of `docs/renderer-semantics.md`")
    print("//! §10). wi/wo are f32 unit vectors: normal incidence, one wo below the surface, random wi")
    print("//! with lobe-centred wo. `eval` is the same for both `sample_visible` settings (checked by")
    print("//! the script); `pdf` is given for both.")
    print()
    print("use matte_render::bsdf::MicrofacetDistribution;")
    print()
    print("/// (wi, wo, eval RGB, pdf with sample_visible = true, pdf with sample_visible = false)")
    print("pub type Row = ([f32; 3], [f32; 3], [f32; 3], f32, f32);")
    ctx = mi.BSDFContext()
    for name, dist, au, av, spec in CONFIGS:
        vis, plain = bsdf(dist, au, av, spec, True), bsdf(dist, au, av, spec, False)
        print()
        print(f"const {name}: &[Row] = &[")
        for wi, wo in directions(rng):
            si = mi.SurfaceInteraction3f()
            si.wi = mi.Vector3f(*map(float, wi))
            w = mi.Vector3f(*map(float, wo))
            e = vis.eval(ctx, si, w)
            e2 = plain.eval(ctx, si, w)
            assert all(abs(a - b) <= 1e-6 * max(1.0, abs(a)) for a, b in zip(e, e2)), (e, e2)
            pv, pp = vis.pdf(ctx, si, w), plain.pdf(ctx, si, w)
            v3 = lambda v: "[" + ", ".join(f(c) for c in v) + "]"
            print(f"    ({v3(wi)}, {v3(wo)}, {v3(list(e))}, {f(pv)}, {f(pp)}),")
        print("];")
    print()
    print("/// (distribution, alpha_u, alpha_v, specular_reflectance, rows); all with Au's §10 eta/k.")
    print("pub type Config = (MicrofacetDistribution, f32, f32, [f32; 3], &'static [Row]);")
    print()
    print("pub const MITSUBA_CONFIGS: &[Config] = &[")
    for name, dist, au, av, spec in CONFIGS:
        s = ", ".join(f(c) for c in spec)
        print(f"    (MicrofacetDistribution::{RUST_DIST[dist]}, {f(au)}, {f(av)}, [{s}], {name}),")
    print("];")


if __name__ == "__main__":
    main()
