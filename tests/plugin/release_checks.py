"""The plugin's core checks under one Mitsuba release, run by `tests/plugin/test_releases.py`
with the Python of that release's environment (`.venvs/mitsuba-<release>`, the wheel installed;
setup/release_venvs.sh). One check per process (Mitsuba 3.8.0 cannot switch from a
scalar render to loading JIT plugins in one process, its own `roughplastic` included), JSON on
its last line of stdout:

    python release_checks.py values VARIANT   # f·cos and pdf of every type on fixed direction pairs
    python release_checks.py render VARIANT   # the Cornell box in wolff, ginneken and eon
    python release_checks.py gradient [TYPE]  # d(image mean)/d(parameter): AD and central differences
    python release_checks.py chi2             # mitsuba.chi2 for ginneken at 45°
    python release_checks.py platform         # the machine and the plugin root matte_mitsuba chose

VARIANT is scalar_rgb or llvm_ad_rgb; llvm runs in Dr.Jit's default (symbolic) mode, `values`
inside a symbolic loop. Several checks of one variant may share a process, each written
CHECK[:ARGUMENT] after --many, the last line then a JSON list of their results in order:

    python release_checks.py --many values:llvm_ad_rgb render:llvm_ad_rgb gradient:ginneken chi2

(where each process costs seconds to start, as under emulation).
"""

import json
import math
import sys

import drjit as dr
import mitsuba as mi
import numpy as np

N = 256
RGB = [0.8, 0.5, 0.2]
RES, SPP = 24, 64


def types():
    """(type, parameters) for every registered type at its defaults, a file parameter
    (tabulated_brdf's table) given the packaged V-cavity table."""
    import matte_mitsuba
    from matte_mitsuba import registry

    table = matte_mitsuba.ground_truth_path("v_cavities_sigma0.3")
    return [(m["name"], {p["name"]: table for p in registry.file_parameters(m)}) for m in registry.MODELS]


def pairs():
    """Fixed float32 unit direction pairs (the same under every release), ~10 % below."""
    rng = np.random.default_rng(7)

    def dirs():
        z = rng.uniform(-0.1, 1.0, N)
        phi = rng.uniform(0, 2 * np.pi, N)
        r = np.sqrt(np.maximum(0.0, 1 - z * z))
        return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1).astype(np.float32)

    return dirs(), dirs()


@dr.syntax
def eval_pdf_in_symbolic_loop(bsdf, si, wo):
    """`bsdf.eval_pdf` recorded inside a symbolic `while` loop (one iteration)."""
    value = dr.zeros(mi.Spectrum, dr.width(wo))
    pdf = dr.zeros(mi.Float, dr.width(wo))
    i = dr.zeros(mi.UInt32, dr.width(wo))
    while i < 1:
        value, pdf = bsdf.eval_pdf(mi.BSDFContext(), si, wo)
        i += 1
    return value, pdf


def values(variant):
    wi, wo = pairs()
    out = {}
    for kind, params in types():
        bsdf = mi.load_dict({"type": kind, "reflectance": {"type": "rgb", "value": RGB}, **params})
        if variant.startswith("scalar"):
            f, pdf = [], []
            si = mi.SurfaceInteraction3f()
            for a, b in zip(wi, wo):
                si.wi = mi.Vector3f(*a)
                v, p = bsdf.eval_pdf(mi.BSDFContext(), si, mi.Vector3f(*b))
                f.append([float(x) for x in v])
                pdf.append(float(p))
        else:
            si = dr.zeros(mi.SurfaceInteraction3f, N)
            si.wi = mi.Vector3f(wi[:, 0], wi[:, 1], wi[:, 2])
            v, p = eval_pdf_in_symbolic_loop(bsdf, si, mi.Vector3f(wo[:, 0], wo[:, 1], wo[:, 2]))
            f = np.array(v).T.tolist()
            pdf = np.array(p).tolist()
        out[kind] = {"f": f, "pdf": pdf}
    return {"wi": wi.tolist(), "wo": wo.tolist(), "types": out}


def cornell(kinds, integrator="path", fixed=None):
    """The Cornell box at RES², its white, red and green materials of the types `kinds` (with
    the parameters `fixed`), no Russian roulette (smooth in the parameters)."""
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = RES
    d["integrator"] = {"type": integrator, "max_depth": 4, "rr_depth": 1000}
    for name, kind in zip(("white", "red", "green"), kinds):
        d[name]["type"] = kind
        d[name].update(fixed or {})
    return mi.load_dict(d)


def render():
    img = np.array(mi.render(cornell(["wolff", "ginneken", "eon"]), spp=SPP), dtype=np.float64)
    return {"image": img.ravel().tolist()}


def gradient(only=None):
    """Per type (or the one named), d(image mean)/d(its first numeric parameter, else the
    reflectance) on the Cornell box whose three materials are that type: prb's adjoint and
    central differences."""
    from matte_mitsuba import registry
    from matte_mitsuba.gradient_check import adjoint_gradient, central_difference, shifted

    out = {}
    for kind, fixed in types():
        if only and kind != only:
            continue
        numeric = registry.numeric_parameters(kind)
        name = numeric[0]["name"] if numeric else "reflectance.value"
        scene = cornell([kind] * 3, "prb", fixed)
        params = mi.traverse(scene)
        key = "white." + name
        with_value = shifted(mi, params, key)
        params[key] = with_value(0.0)
        ad = float(np.sum(adjoint_gradient(mi, scene, params, key, 8, 3)))
        fd = central_difference(mi, scene, params, key, with_value, 1e-2, 8, 3)
        out[kind] = {"parameter": name, "ad": ad, "fd": fd}
    return out


def chi2():
    t = math.radians(45.0)
    sample_func, pdf_func = mi.chi2.BSDFAdapter("ginneken", "", wi=[math.sin(t), 0.0, math.cos(t)])
    test = mi.chi2.ChiSquareTest(
        domain=mi.chi2.SphericalDomain(), sample_func=sample_func, pdf_func=pdf_func, sample_dim=3
    )
    return {"passed": bool(test.run()), "messages": test.messages}


def variant_of(check, arg):
    """The variant a check runs in: its argument for values and render, else llvm_ad_rgb."""
    return arg if arg and check in ("values", "render") else "llvm_ad_rgb"


def platform_check():
    import platform

    import matte_mitsuba

    return {"machine": platform.machine(), "plugin_root": matte_mitsuba.PLUGIN_ROOT}


def run(check, arg, variant):
    checks = {
        "values": lambda: values(variant),
        "render": render,
        "gradient": lambda: {"types": gradient(arg)},
        "chi2": chi2,
        "platform": platform_check,
    }
    return {"check": check, "variant": variant, "mitsuba": mi.__version__, **checks[check]()}


def main():
    many = None
    if sys.argv[1] == "--many":
        many = [(word.partition(":")[0], word.partition(":")[2] or None) for word in sys.argv[2:]]
    todo = many or [(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else None)]
    variants = {variant_of(check, arg) for check, arg in todo}
    if len(variants) != 1:
        sys.exit(f"release_checks: one variant per process (Mitsuba 3.8.0 cannot switch), got {sorted(variants)}")
    (variant,) = variants
    mi.set_variant(variant)
    import matte_mitsuba  # noqa: F401  (registers the plugins of the running release)

    results = [run(check, arg, variant) for check, arg in todo]
    print("\n" + json.dumps(results if many else results[0]))  # the last line (Mitsuba's chi2 prints to stdout)


if __name__ == "__main__":
    main()
