"""Textured numeric parameters of matte's plugins, every numeric parameter of every registered
type (σ, r, α, int_ior, ext_ior, m; docs/models.md#spatially-varying-parameters).

Oracles: central finite differences of the same function (for the gradients that reach the
texture's data through `mi.traverse`), the float form of each parameter (a texture with the
same value everywhere must give the float's BSDF and, summed over its texels, the float's
gradient), and Mitsuba's own error reporting for refused forms.
"""

import math

import numpy as np
import pytest
from conftest import random_pairs
from matte_mitsuba import registry
from matte_mitsuba.gradient_check import adjoint_gradient, image_mean

N = 4000
# (type, textured parameter, value, fixed parameters, relative tolerance against the float form):
# the values and options chosen for each model here, then every other one from the registry.
CASES = [
    ("oren_nayar", "sigma", 0.4, {}, 1e-5),
    ("oren_nayar", "sigma", 0.7, {"model": "full"}, 1e-5),
    ("eon", "roughness", 0.6, {}, 1e-5),
    ("burley", "roughness", 0.6, {}, 1e-5),
    ("roughdiffuse", "alpha", 0.5, {}, 1e-5),
    ("wolff", "int_ior", 1.6, {}, 2e-4),  # F_dr from its fit (|error| <= 2e-5)
    ("wolff", "ext_ior", 1.2, {"int_ior": 1.9, "normalization": "normal"}, 2e-4),
    # tables over m (Hermite in m) against the table built for m = 0.35
    ("ginneken", "roughness", 0.35, {}, 5e-3),
]


def _other_value(m, p):
    """A value of a numeric parameter away from its default, for a model with no case above: a
    quarter of the way from the default to the upper end of its fit range (where `matte fit`
    searches it, within its valid range)."""
    default = float(registry.default(p))
    return default + 0.25 * (registry.fit_range(m, p["name"])[1] - default)


# Every other numeric parameter of every registered type (a new model's too), the other
# parameters at their defaults, to the float form's precision.
CASES += [
    (m["name"], p["name"], _other_value(m, p), {}, 1e-5)
    for m in registry.MODELS
    for p in registry.numeric_parameters(m)
    if (m["name"], p["name"]) not in {(kind, name) for kind, name, _, _, _ in CASES}
]
# The float's gradient against the constant texture's: the same function except Wolff's F_dr
# (fit: its n-derivative is within 0.11 % for n in [1.1, 4]) and van Ginneken (its first-order
# ∂/∂m table at m₀ against the Hermite interpolation over m).
GRADIENT_TOLERANCE = {"wolff": 3e-3, "ginneken": 1e-2}


def test_every_numeric_parameter_of_every_registered_type_has_a_case():
    declared = {(m["name"], p["name"]) for m in registry.MODELS for p in registry.numeric_parameters(m)}
    covered = {(kind, name) for kind, name, _, _, _ in CASES}
    assert declared <= covered, f"no textured case for {sorted(declared - covered)}"


def case_id(case):
    kind, name, value, fixed, _ = case
    return f"{kind}-{name}" + "".join(f"-{k}={v}" for k, v in fixed.items())


def bitmap(mi, values):
    """A 1-channel raw bitmap texture of the 2-D array `values` (bilinear, repeat)."""
    arr = np.asarray(values, dtype=np.float32)[..., None]
    return {"type": "bitmap", "raw": True, "bitmap": mi.Bitmap(arr)}


def load(mi, kind, fixed, name, value):
    d = {"type": kind, "reflectance": {"type": "rgb", "value": [0.8, 0.5, 0.3]}}
    d.update(fixed)
    d[name] = value
    return mi.load_dict(d)


def interaction(mi, n, seed):
    import drjit as dr

    wi, wo = random_pairs(n, seed)
    uv = np.random.default_rng(seed + 1).uniform(0, 1, (n, 2)).astype(np.float32)
    si = dr.zeros(mi.SurfaceInteraction3f, n)
    si.wi = mi.Vector3f(wi.T)
    si.uv = mi.Point2f(uv.T)
    si.n = mi.Normal3f(0, 0, 1)
    si.sh_frame = mi.Frame3f(si.n)
    return si, mi.Vector3f(wo.T)


def evaluate(mi, bsdf, si, wo):
    """eval, pdf and a sample's weight and direction, as float64 arrays."""
    ctx = mi.BSDFContext()
    value, pdf = bsdf.eval_pdf(ctx, si, wo)
    n = np.size(np.array(pdf))
    u = np.random.default_rng(9).uniform(0, 1, (2, n)).astype(np.float32)
    bs, weight = bsdf.sample(ctx, si, 0.5, mi.Point2f(u) if n > 1 else mi.Point2f(float(u[0, 0]), float(u[1, 0])))
    return [np.array(x, dtype=np.float64) for x in (value, pdf, weight, bs.wo)]


@pytest.mark.parametrize("case", CASES, ids=case_id)
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb", "scalar_rgb"], indirect=True)
def test_constant_texture_equals_the_float(mi_variant, case):
    mi = mi_variant
    kind, name, value, fixed, tol = case
    as_float = load(mi, kind, fixed, name, value)
    as_texture = load(mi, kind, fixed, name, bitmap(mi, [[value, value], [value, value]]))
    if mi.variant().startswith("scalar"):
        wi, wo = random_pairs(200, 5)
        rows = []
        for k in range(len(wi)):
            si = mi.SurfaceInteraction3f()
            si.wi, si.uv = mi.Vector3f(wi[k]), mi.Point2f(0.3, 0.7)
            si.n = mi.Normal3f(0, 0, 1)
            si.sh_frame = mi.Frame3f(si.n)
            rows.append([evaluate(mi, b, si, mi.Vector3f(wo[k])) for b in (as_float, as_texture)])
        got = [[np.array([r[j][i] for r in rows]) for i in range(4)] for j in range(2)]
    else:
        si, wo = interaction(mi, N, 5)
        got = [evaluate(mi, b, si, wo) for b in (as_float, as_texture)]
    for i, what in enumerate(["eval", "pdf", "sample weight", "sample direction"]):
        a, b = got[0][i], got[1][i]
        assert np.isfinite(b).all(), what
        err = np.abs(a - b).max() / max(np.abs(a).max(), 1e-12)
        assert err <= tol, f"{what}: textured differs from the float by {err:.2e} (relative to its maximum)"


@pytest.mark.parametrize("case", CASES, ids=case_id)
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_texture_gradient_matches_finite_differences(mi_variant, case):
    """d(Σ eval)/d(texel) for each texel of a 2×2 bilinear texture with four different values
    (uv spread over the texture, so every texel contributes), against central differences of
    the same sum; and the four texel gradients of a constant texture sum to the float's."""
    mi = mi_variant
    import drjit as dr

    kind, name, value, fixed, _ = case
    texels = np.array([[value, value * 1.1], [value * 0.9, value * 1.05]])
    if name == "int_ior":
        texels = np.maximum(texels, 1.05)
    if kind == "ginneken":  # one texel per cell of the roughness axis, no node crossed by ±h
        texels = np.array([[0.13, 0.22], [0.33, 0.46]])
    bsdf = load(mi, kind, fixed, name, bitmap(mi, texels))
    params = mi.traverse(bsdf)
    key = name + ".data"
    assert key in params, list(params.keys())
    si, wo = interaction(mi, N, 11)
    ctx = mi.BSDFContext()

    def total(data):
        params[key] = mi.TensorXf(np.asarray(data, dtype=np.float32).reshape(2, 2, 1))
        params.update()
        return float(np.array(bsdf.eval(ctx, si, wo), dtype=np.float64).sum())

    params[key] = mi.TensorXf(texels.astype(np.float32).reshape(2, 2, 1))
    dr.enable_grad(params[key])
    params.update()
    dr.backward(dr.sum(bsdf.eval(ctx, si, wo), axis=None))
    ad = np.array(dr.grad(params[key]), dtype=np.float64).ravel()
    assert np.isfinite(ad).all()
    h = 1e-2 * value
    for k in range(4):
        plus, minus = texels.ravel().copy(), texels.ravel().copy()
        plus[k] += h
        minus[k] -= h
        fd = (total(plus) - total(minus)) / (2 * h)
        print(f"{case_id(case)} texel {k}: AD {ad[k]:.6g} FD {fd:.6g}")
        assert abs(fd) > 1e-3, fd
        assert abs(ad[k] - fd) <= 5e-3 * abs(fd), f"texel {k}: AD {ad[k]} vs FD {fd}"

    # The float's gradient equals the constant texture's gradient summed over its texels.
    flat = load(mi, kind, fixed, name, value)
    fp = mi.traverse(flat)
    dr.enable_grad(fp[name])
    fp.update()
    dr.backward(dr.sum(flat.eval(ctx, si, wo), axis=None))
    g_float = float(np.array(dr.grad(fp[name]))[0])
    const = load(mi, kind, fixed, name, bitmap(mi, [[value, value], [value, value]]))
    cp = mi.traverse(const)
    dr.enable_grad(cp[key])
    cp.update()
    dr.backward(dr.sum(const.eval(ctx, si, wo), axis=None))
    g_texels = float(np.array(dr.grad(cp[key]), dtype=np.float64).sum())
    assert abs(g_texels - g_float) <= GRADIENT_TOLERANCE.get(kind, 2e-5) * abs(g_float), (g_texels, g_float)


# Every finite bound of every numeric parameter's lane clamp (its range, or van Ginneken's
# roughness axis from 0.02), with a texel 0.5 beyond it.
BOUNDS = [
    (m["name"], p["name"], bound, beyond)
    for m in registry.MODELS
    for p in registry.numeric_parameters(m)
    for bound, beyond in zip(registry.lane_clamp(m, p["name"]), (-0.5, 0.5))
    if math.isfinite(bound)
]


@pytest.mark.parametrize("kind, name, bound, beyond", BOUNDS, ids=[f"{k}-{n}={b}" for k, n, b, _ in BOUNDS])
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_texture_at_and_beyond_the_bounds_is_finite(mi_variant, kind, name, bound, beyond):
    """Texels at the bound and beyond it (clamped) give finite values and gradients: the
    finiteness rule of docs/traced-kernels.md holds per lane."""
    mi = mi_variant
    import drjit as dr

    bsdf = load(mi, kind, {}, name, bitmap(mi, [[bound, bound + beyond], [bound, bound]]))
    params = mi.traverse(bsdf)
    dr.enable_grad(params[name + ".data"])
    params.update()
    si, wo = interaction(mi, N, 3)
    value = bsdf.eval(mi.BSDFContext(), si, wo)
    dr.backward(dr.sum(value, axis=None))
    assert np.isfinite(np.array(value)).all()
    assert np.isfinite(np.array(dr.grad(params[name + ".data"]))).all()


@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_render_gradient_of_a_textured_sigma(mi_variant):
    """A small render (prb) of a plane whose σ is a 2×2 texture: d(image mean)/d(texel) by the
    adjoint pass with the primal's seed, against central differences of renders, within 1 %."""
    mi = mi_variant
    texels = np.array([[0.2, 0.5], [0.8, 0.35]], dtype=np.float32)
    scene = mi.load_dict(
        {
            "type": "scene",
            "integrator": {"type": "prb", "max_depth": 2},
            "sensor": {
                "type": "perspective",
                "fov": 50,
                "to_world": mi.ScalarTransform4f().look_at(origin=[0, -2, 2.5], target=[0, 0, 0], up=[0, 0, 1]),
                "film": {"type": "hdrfilm", "width": 16, "height": 16},
            },
            "light": {"type": "directional", "direction": [0.6, -0.4, -1], "irradiance": {"type": "rgb", "value": 3.0}},
            "plane": {
                "type": "rectangle",
                "bsdf": {
                    "type": "oren_nayar",
                    "sigma": bitmap(mi, texels),
                    "reflectance": {"type": "rgb", "value": 0.7},
                },
            },
        }
    )
    params = mi.traverse(scene)
    key = "plane.bsdf.sigma.data"
    spp, seed = 16, 2

    def mean(data):
        params[key] = mi.TensorXf(np.asarray(data, dtype=np.float32).reshape(2, 2, 1))
        params.update()
        return image_mean(mi, scene, params, spp, seed)

    params[key] = mi.TensorXf(texels.reshape(2, 2, 1))
    ad = adjoint_gradient(mi, scene, params, key, spp, seed)
    h = 1e-2
    for k in range(4):
        plus, minus = texels.ravel().copy(), texels.ravel().copy()
        plus[k] += h
        minus[k] -= h
        fd = (mean(plus) - mean(minus)) / (2 * h)
        print(f"texel {k}: AD {ad[k]:.6g} FD {fd:.6g}")
        assert abs(fd) > 1e-5, fd
        assert abs(ad[k] - fd) <= 0.01 * abs(fd), f"texel {k}: AD {ad[k]} vs FD {fd}"


@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb", "scalar_rgb"], indirect=True)
def test_refused_textures_raise(mi_variant):
    mi = mi_variant
    with pytest.raises(RuntimeError, match='parameter "model": is not a numeric parameter'):
        mi.load_dict({"type": "oren_nayar", "model": {"type": "checkerboard"}})


NAN_CASES = sorted({(kind, name) for kind, name, _, _, _ in CASES})


@pytest.mark.parametrize("kind, name", NAN_CASES, ids=[f"{k}-{n}" for k, n in NAN_CASES])
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_nan_texels_clamp_to_the_lower_bound_as_in_scalar(mi_variant, kind, name):
    """A NaN texel is clamped to the parameter's lower bound (rust/brdf/src/lane.rs): the traced
    kernel's `min`/`max` must drop a NaN operand (Dr.Jit's `fmin`/`fmax`; its `minimum` and
    `maximum` propagate NaN since 1.5.0), as the CPU kernels do. The same texture in
    llvm_ad_rgb and in scalar_rgb (a separate process) gives the same, finite values."""
    mi = mi_variant
    nan = float("nan")
    bsdf = load(mi, kind, {}, name, bitmap(mi, [[nan, nan], [nan, nan]]))
    si, wo = interaction(mi, 64, 11)
    traced = np.array(bsdf.eval(mi.BSDFContext(), si, wo), dtype=np.float64)
    assert np.isfinite(traced).all(), f"{kind}.{name}: {np.isnan(traced).sum()} NaN values in llvm_ad_rgb"
    wi, wo_np = random_pairs(64, 11)
    code = (
        "import json, sys, numpy as np, mitsuba as mi\n"
        "mi.set_variant('scalar_rgb')\nimport matte_mitsuba\n"
        f"b = mi.load_dict({{'type': {kind!r}, 'reflectance': {{'type': 'rgb', 'value': [0.8, 0.5, 0.3]}},"
        f" {name!r}: {{'type': 'bitmap', 'raw': True, 'bitmap': mi.Bitmap(np.full((2, 2, 1), np.nan, np.float32))}}}})\n"
        "wi, wo = json.load(sys.stdin)\nout = []\n"
        "for a, c in zip(wi, wo):\n"
        "    si = mi.SurfaceInteraction3f(); si.wi = mi.Vector3f(a); si.uv = mi.Point2f(0.5, 0.5)\n"
        "    si.n = mi.Normal3f(0, 0, 1); si.sh_frame = mi.Frame3f(si.n)\n"
        "    out.append(list(b.eval(mi.BSDFContext(), si, mi.Vector3f(c))))\n"
        "print(json.dumps(out))\n"
    )
    import json
    import subprocess
    import sys

    r = subprocess.run(
        [sys.executable, "-c", code], input=json.dumps([wi.tolist(), wo_np.tolist()]), capture_output=True, text=True
    )
    assert r.returncode == 0, r.stderr
    scalar = np.array(json.loads(r.stdout), dtype=np.float64).T
    assert np.isfinite(scalar).all()
    err = np.abs(traced - scalar).max() / max(np.abs(scalar).max(), 1e-12)
    assert err <= 1e-4, f"{kind}.{name}: llvm_ad_rgb differs from scalar_rgb by {err:.2e}"
