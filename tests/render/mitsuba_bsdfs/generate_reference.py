#!/usr/bin/env python3
"""Writes tests/render/mitsuba_bsdfs/reference.rs: eval/pdf (and, for the BSDFs whose sampling
warp matte reproduces exactly, sample) values of the real Mitsuba 3.9.1 for the BSDF
configurations listed below.

Run once with the pinned wheel (mitsuba==3.9.1, drjit==1.5.0), e.g.

    /work/main/.venv/bin/python tests/render/mitsuba_bsdfs/generate_reference.py

The output is committed; the Rust test suite never runs Mitsuba. Each configuration is one
XML `<bsdf>` element, loaded as-is by Mitsuba (`mi.load_string`) and by matte's scene
loader, so the test also checks that matte reads the same parameters and defaults.
"""

import os
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")

# (name, XML, directions: "upper" = both in the upper hemisphere (+ a few below),
#  "sphere" = wi and wo anywhere, with lobe-centred wo; sample rows?)
CONFIGS = [
    ("plastic_default", '<bsdf type="plastic"/>', "upper", True),
    (
        "plastic_coloured",
        '<bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.2, 0.5, 0.8"/>'
        '<rgb name="specular_reflectance" value="0.9, 0.8, 0.7"/><float name="int_ior" value="1.7"/></bsdf>',
        "upper",
        True,
    ),
    (
        "plastic_nonlinear",
        '<bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.7, 0.5, 0.1"/>'
        '<boolean name="nonlinear" value="true"/><string name="int_ior" value="water"/><string name="ext_ior" value="air"/></bsdf>',
        "upper",
        True,
    ),
    ("roughplastic_default", '<bsdf type="roughplastic"/>', "upper", False),
    (
        "roughplastic_ggx",
        '<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="alpha" value="0.3"/>'
        '<rgb name="diffuse_reflectance" value="0.2, 0.5, 0.8"/><boolean name="nonlinear" value="true"/></bsdf>',
        "upper",
        False,
    ),
    (
        "roughplastic_beckmann_plain",
        '<bsdf type="roughplastic"><float name="alpha" value="0.5"/><boolean name="sample_visible" value="false"/>'
        '<rgb name="specular_reflectance" value="0.9, 0.8, 0.7"/><float name="int_ior" value="1.9"/></bsdf>',
        "upper",
        False,
    ),
    (
        "roughplastic_ggx_sharp",
        '<bsdf type="roughplastic"><string name="distribution" value="GGX"/><float name="alpha" value="0.05"/>'
        '<float name="int_ior" value="1.33"/><rgb name="diffuse_reflectance" value="0.9, 0.1, 0.4"/></bsdf>',
        "upper",
        False,
    ),
    ("roughdielectric_default", '<bsdf type="roughdielectric"/>', "sphere", False),
    (
        "roughdielectric_ggx",
        '<bsdf type="roughdielectric"><string name="distribution" value="ggx"/><float name="alpha" value="0.3"/>'
        '<float name="int_ior" value="1.33"/></bsdf>',
        "sphere",
        False,
    ),
    (
        "roughdielectric_aniso_plain",
        '<bsdf type="roughdielectric"><string name="distribution" value="ggx"/><float name="alpha_u" value="0.1"/>'
        '<float name="alpha_v" value="0.4"/><boolean name="sample_visible" value="false"/></bsdf>',
        "sphere",
        False,
    ),
    (
        "roughdielectric_beckmann_tinted",
        '<bsdf type="roughdielectric"><float name="alpha" value="0.5"/>'
        '<rgb name="specular_reflectance" value="0.9, 0.8, 0.7"/><rgb name="specular_transmittance" value="0.3, 0.6, 0.9"/>'
        '<float name="int_ior" value="1.2"/><float name="ext_ior" value="1.5"/></bsdf>',
        "sphere",
        False,
    ),
    ("thindielectric_default", '<bsdf type="thindielectric"/>', "sphere", True),
    (
        "thindielectric_tinted",
        '<bsdf type="thindielectric"><float name="int_ior" value="1.7"/>'
        '<rgb name="specular_reflectance" value="0.9, 0.8, 0.7"/><rgb name="specular_transmittance" value="0.3, 0.6, 0.9"/></bsdf>',
        "sphere",
        True,
    ),
    # Named conductors beyond Au/Cu/Ag/Al (the spectral tables' RGB values).
    ("conductor_a-C", '<bsdf type="conductor"><string name="material" value="a-C"/></bsdf>', "upper", True),
    ("conductor_Cr", '<bsdf type="conductor"><string name="material" value="Cr"/></bsdf>', "upper", True),
    (
        "roughconductor_W",
        '<bsdf type="roughconductor"><string name="material" value="W"/><string name="distribution" value="ggx"/>'
        '<float name="alpha" value="0.2"/></bsdf>',
        "upper",
        False,
    ),
    (
        "roughconductor_TiO2-e_palik",
        '<bsdf type="roughconductor"><string name="material" value="TiO2-e_palik"/>'
        '<float name="alpha" value="0.3"/></bsdf>',
        "upper",
        False,
    ),
    # normalmap: a constant tangent-space normal (2·rgb − 1) around several nested BSDFs.
    (
        "normalmap_diffuse",
        '<bsdf type="normalmap"><rgb name="normalmap" value="0.8, 0.5, 0.7"/>'
        '<bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf></bsdf>',
        "upper",
        True,
    ),
    (
        "normalmap_plastic_noshadow",
        '<bsdf type="normalmap"><rgb name="normalmap" value="0.35, 0.6, 0.85"/>'
        '<boolean name="use_shadowing_function" value="false"/><bsdf type="plastic"/></bsdf>',
        "upper",
        True,
    ),
    (
        "normalmap_roughplastic_noflip",
        '<bsdf type="normalmap"><rgb name="normalmap" value="0.6, 0.45, 0.9"/>'
        '<boolean name="flip_invalid_normals" value="false"/><bsdf type="roughplastic"><string name="distribution" value="ggx"/>'
        '<float name="alpha" value="0.2"/></bsdf></bsdf>',
        "upper",
        False,
    ),
    (
        "normalmap_roughconductor",
        '<bsdf type="normalmap"><rgb name="normalmap" value="0.3, 0.7, 0.8"/>'
        '<bsdf type="roughconductor"><string name="material" value="Cu"/><float name="alpha" value="0.3"/></bsdf></bsdf>',
        "upper",
        False,
    ),
    # principled: defaults, every lobe, glass, anisotropic metal, sampling rates / zero flags.
    ("principled_default", '<bsdf type="principled"/>', "sphere", False),
    (
        "principled_full",
        '<bsdf type="principled"><rgb name="base_color" value="0.8, 0.4, 0.2"/><float name="roughness" value="0.4"/>'
        '<float name="metallic" value="0.3"/><float name="spec_tint" value="0.5"/><float name="sheen" value="0.6"/>'
        '<float name="sheen_tint" value="0.4"/><float name="clearcoat" value="0.7"/><float name="clearcoat_gloss" value="0.5"/>'
        '<float name="flatness" value="0.3"/><float name="anisotropic" value="0.5"/><float name="specular" value="0.6"/></bsdf>',
        "sphere",
        False,
    ),
    (
        "principled_glass",
        '<bsdf type="principled"><rgb name="base_color" value="0.9, 0.95, 0.7"/><float name="spec_trans" value="0.8"/>'
        '<float name="roughness" value="0.3"/><float name="eta" value="1.45"/></bsdf>',
        "sphere",
        False,
    ),
    (
        "principled_metal_aniso",
        '<bsdf type="principled"><rgb name="base_color" value="0.9, 0.6, 0.3"/><float name="metallic" value="1"/>'
        '<float name="anisotropic" value="0.8"/><float name="roughness" value="0.35"/></bsdf>',
        "sphere",
        False,
    ),
    (
        "principled_rates",
        '<bsdf type="principled"><float name="spec_trans" value="0.5"/><float name="clearcoat" value="0.5"/>'
        '<float name="metallic" value="0"/><float name="main_specular_sampling_rate" value="2"/>'
        '<float name="clearcoat_sampling_rate" value="0.5"/><float name="diffuse_reflectance_sampling_rate" value="3"/>'
        '<float name="roughness" value="0.6"/><float name="specular" value="0.3"/></bsdf>',
        "sphere",
        False,
    ),
    # principledthin: defaults, every lobe, sampling rates.
    ("principledthin_default", '<bsdf type="principledthin"/>', "sphere", False),
    (
        "principledthin_full",
        '<bsdf type="principledthin"><rgb name="base_color" value="0.3, 0.6, 0.9"/><float name="roughness" value="0.35"/>'
        '<float name="spec_trans" value="0.6"/><float name="diff_trans" value="0.8"/><float name="eta" value="1.33"/>'
        '<float name="spec_tint" value="0.4"/><float name="sheen" value="0.5"/><float name="sheen_tint" value="0.3"/>'
        '<float name="flatness" value="0.4"/><float name="anisotropic" value="0.6"/></bsdf>',
        "sphere",
        False,
    ),
    (
        "principledthin_rates",
        '<bsdf type="principledthin"><float name="spec_trans" value="0.4"/><float name="diff_trans" value="1.2"/>'
        '<float name="specular_reflectance_sampling_rate" value="2"/><float name="specular_transmittance_sampling_rate" value="0.5"/>'
        '<float name="diffuse_transmittance_sampling_rate" value="3"/><float name="diffuse_reflectance_sampling_rate" value="0.7"/>'
        '<float name="roughness" value="0.7"/></bsdf>',
        "sphere",
        False,
    ),
    # mask: nested BSDF times the opacity; sampling picks the pass-through with 1 - opacity.
    (
        "mask_diffuse",
        '<bsdf type="mask"><float name="opacity" value="0.3"/>'
        '<bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf></bsdf>',
        "upper",
        True,
    ),
    (
        "mask_default_roughplastic",
        '<bsdf type="mask"><bsdf type="roughplastic"><string name="distribution" value="ggx"/>'
        '<float name="alpha" value="0.2"/></bsdf></bsdf>',
        "upper",
        False,
    ),
    # blendbsdf: blended eval/pdf; the sample is the one-sample MIS blend of both.
    (
        "blend_diffuse_plastic",
        '<bsdf type="blendbsdf"><float name="weight" value="0.3"/>'
        '<bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf><bsdf type="plastic"/></bsdf>',
        "upper",
        True,
    ),
    (
        "blend_roughconductor_diffuse",
        '<bsdf type="blendbsdf"><float name="weight" value="0.65"/>'
        '<bsdf type="roughconductor"><string name="material" value="Au"/><float name="alpha" value="0.25"/></bsdf>'
        '<bsdf type="diffuse"/></bsdf>',
        "upper",
        False,
    ),
]

rng = np.random.default_rng(20261201)


def unit(v):
    v = np.asarray(v, dtype=np.float64)
    return (v / np.linalg.norm(v)).astype(np.float32)


def rand_sphere():
    return unit(rng.normal(size=3))


def rand_upper():
    v = rand_sphere()
    return np.array([v[0], v[1], abs(v[2])], dtype=np.float32)


def refract(wi, eta):
    """Refracted direction through the flat interface (None under TIR)."""
    eta_i = eta if wi[2] > 0 else 1.0 / eta  # eta_t / eta_i
    cos_i = abs(wi[2])
    sin2_t = (1 - cos_i * cos_i) / (eta_i * eta_i)
    if sin2_t >= 1:
        return None
    cos_t = np.sqrt(1 - sin2_t)
    t = -wi / eta_i
    t[2] = -np.sign(wi[2]) * cos_t
    return unit(t)


def directions(kind, n=24):
    pairs = [(np.array([0, 0, 1], np.float32), np.array([0, 0, 1], np.float32))]
    for i in range(n):
        if kind == "upper":
            wi = rand_upper()
            if i % 3 == 0:
                wo = unit(np.array([-wi[0], -wi[1], wi[2]]) + 0.3 * rng.normal(size=3))
                wo[2] = abs(wo[2])
                wo = unit(wo)
            else:
                wo = rand_upper()
            if i == n - 1:
                wo = np.array([wo[0], wo[1], -wo[2]], np.float32)
        else:
            wi = rand_sphere()
            if i % 3 == 0:
                wo = unit(np.array([-wi[0], -wi[1], wi[2]]) + 0.2 * rng.normal(size=3))
            elif i % 3 == 1:
                t = refract(wi.astype(np.float64), 1.5)
                wo = unit((t if t is not None else -wi) + 0.2 * rng.normal(size=3))
            else:
                wo = rand_sphere()
        pairs.append((wi, wo))
    return pairs


def f32(x):
    return f"{float(np.float32(x))!r}".replace("inf", "f32::INFINITY")


def vec(v):
    return "[" + ", ".join(f32(x) for x in v) + "]"


def main(out_path):
    ctx = mi.BSDFContext()
    lines = [
        "//! Generated by `tests/render/mitsuba_bsdfs/generate_reference.py`; do not edit (rerun it).",
        "//! Expected values of the real Mitsuba 3.9.1 (PyPI wheel `mitsuba==3.9.1`, `drjit==1.5.0`,",
        "//! variant `scalar_rgb`).",
        "//! Each configuration is the XML that both Mitsuba (`mi.load_string`) and matte load.",
        "",
        "/// (wi, wo, eval RGB = f·|cos θo|, pdf)",
        "pub type EvalRow = ([f32; 3], [f32; 3], [f32; 3], f32);",
        "/// (wi, sample1, sample2, wo, weight RGB, pdf)",
        "pub type SampleRow = ([f32; 3], f32, [f32; 2], [f32; 3], [f32; 3], f32);",
        "",
        "pub struct Config {",
        "    pub name: &'static str,",
        "    pub xml: &'static str,",
        "    pub eval: &'static [EvalRow],",
        "    pub sample: &'static [SampleRow],",
        "}",
        "",
        "pub const CONFIGS: &[Config] = &[",
    ]
    for name, xml, kind, with_sample in CONFIGS:
        bsdf = mi.load_string(xml.replace("<bsdf ", '<bsdf version="3.0.0" ', 1))
        rows = []
        for wi, wo in directions(kind):
            si = mi.SurfaceInteraction3f()
            si.wi = mi.Vector3f(*map(float, wi))
            wo_m = mi.Vector3f(*map(float, wo))
            e = bsdf.eval(ctx, si, wo_m)
            p = bsdf.pdf(ctx, si, wo_m)
            rows.append(f"        ({vec(wi)}, {vec(wo)}, {vec([e[0], e[1], e[2]])}, {f32(p)}),")
        srows = []
        if with_sample:
            for _i in range(24):
                wi = rand_upper() if kind == "upper" else rand_sphere()
                s1 = np.float32(rng.random())
                s2 = rng.random(2).astype(np.float32)
                si = mi.SurfaceInteraction3f()
                si.wi = mi.Vector3f(*map(float, wi))
                bs, w = bsdf.sample(ctx, si, float(s1), mi.Point2f(float(s2[0]), float(s2[1])))
                srows.append(
                    f"        ({vec(wi)}, {f32(s1)}, {vec(s2)}, {vec([bs.wo[0], bs.wo[1], bs.wo[2]])}, "
                    f"{vec([w[0], w[1], w[2]])}, {f32(bs.pdf)}),"
                )
        lines.append("    Config {")
        lines.append(f"        name: {name!r},".replace("'", '"'))
        lines.append(f'        xml: r#"{xml}"#,')
        lines.append("        eval: &[")
        lines += ["    " + r for r in rows]
        lines.append("        ],")
        lines.append("        sample: &[")
        lines += ["    " + r for r in srows]
        lines.append("        ],")
        lines.append("    },")
    lines.append("];")
    with open(out_path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {out_path}: {len(CONFIGS)} configurations")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference.rs"))
