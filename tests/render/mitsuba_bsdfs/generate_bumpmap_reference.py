#!/usr/bin/env python3
"""Writes tests/render/mitsuba_bsdfs/bumpmap_reference.rs: Mitsuba 3.9.1's `bumpmap` eval/pdf for a
small generated height map (5x4 grey texels, raw, bilinear, repeat) at hits with explicit
dp/du, dp/dv, geometric normal and shading frame (`scalar_rgb`). Run once with the pinned
wheel:

    /work/main/.venv/bin/python tests/render/mitsuba_bsdfs/generate_bumpmap_reference.py
"""

import os

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
rng = np.random.default_rng(7)
W, H = 5, 4
grey = rng.random((H, W)).astype(np.float32)
texels = np.repeat(grey[:, :, None], 3, axis=2)

NESTED = [
    '<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="alpha" value="0.3"/></bsdf>',
    '<bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf>',
]
SCALES = [0.3, 0.05]


def unit(v):
    v = np.asarray(v, np.float64)
    return (v / np.linalg.norm(v)).astype(np.float32)


def f(x):
    return repr(float(np.float32(x)))


def vec(v):
    return "[" + ", ".join(f(x) for x in v) + "]"


rows = []
for k, (nested, scale) in enumerate(zip(NESTED, SCALES)):
    nested_obj = mi.load_string(nested.replace("<bsdf ", '<bsdf version="3.0.0" ', 1))
    bsdf = mi.load_dict(
        {
            "type": "bumpmap",
            "tex": {"type": "bitmap", "bitmap": mi.Bitmap(texels), "raw": True},
            "scale": scale,
            "nested": nested_obj,
        }
    )
    for i in range(16):
        n_geo = unit(rng.normal(size=3))
        n_sh = unit(n_geo + 0.2 * rng.normal(size=3))
        dp_du = (rng.normal(size=3) * 2).astype(np.float32)
        dp_dv = np.cross(n_geo, dp_du).astype(np.float32) + (0.3 * rng.normal(size=3)).astype(np.float32)
        uv = rng.random(2).astype(np.float32) * 2 - 0.5
        wi = unit(rng.normal(size=3))
        wi[2] = abs(wi[2])
        wo = unit(rng.normal(size=3))
        wo[2] = abs(wo[2]) if i % 5 else -abs(wo[2])
        si = mi.SurfaceInteraction3f()
        si.n = mi.Normal3f(*map(float, n_geo))
        si.sh_frame = mi.Frame3f(mi.Vector3f(*map(float, n_sh)))
        si.dp_du = mi.Vector3f(*map(float, dp_du))
        si.dp_dv = mi.Vector3f(*map(float, dp_dv))
        si.uv = mi.Point2f(float(uv[0]), float(uv[1]))
        si.wi = mi.Vector3f(*map(float, wi))
        ctx = mi.BSDFContext()
        e = bsdf.eval(ctx, si, mi.Vector3f(*map(float, wo)))
        p = bsdf.pdf(ctx, si, mi.Vector3f(*map(float, wo)))
        fr = si.sh_frame
        rows.append(
            f"    ({k}, {vec(n_geo)}, {vec([fr.s[0], fr.s[1], fr.s[2]])}, {vec([fr.t[0], fr.t[1], fr.t[2]])}, "
            f"{vec([fr.n[0], fr.n[1], fr.n[2]])}, {vec(dp_du)}, {vec(dp_dv)}, {vec(uv)}, {vec(wi)}, {vec(wo)}, "
            f"{vec([e[0], e[1], e[2]])}, {f(p)}),"
        )

out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bumpmap_reference.rs")
with open(out, "w") as fh:
    fh.write("//! Mitsuba 3.9.1 `bumpmap` values, written by `generate_bumpmap_reference.py`. Do not edit.\n\n")
    fh.write(f"pub const WIDTH: u32 = {W};\npub const HEIGHT: u32 = {H};\n")
    fh.write(
        "/// Grey height texels, row-major, top row first.\n#[rustfmt::skip]\npub const TEXELS: &[f32] = &["
        + ", ".join(f(x) for x in grey.ravel())
        + "];\n"
    )
    fh.write(
        "/// (nested, scale) per configuration index.\npub const NESTED: &[(&str, f32)] = &[\n"
        + "".join(f'    (r#"{n}"#, {f(s)}),\n' for n, s in zip(NESTED, SCALES))
        + "];\n"
    )
    fh.write("/// (config, n_geo, sh_frame s, t, n, dp_du, dp_dv, uv, wi (local), wo (local), eval RGB, pdf)\n")
    fh.write(
        "pub type Row = (usize, [f32; 3], [f32; 3], [f32; 3], [f32; 3], [f32; 3], [f32; 3], [f32; 2], [f32; 3], [f32; 3], [f32; 3], f32);\n"
    )
    fh.write("#[rustfmt::skip]\npub const ROWS: &[Row] = &[\n" + "\n".join(rows) + "\n];\n")
print("wrote", out)
