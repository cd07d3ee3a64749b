"""The plugin's eval divided by cos θo equals the Rust kernel (`matte brdf --pairs`) on 10^4
random direction pairs to 1e-5 relative, for every type and several parameter sets, in
scalar_rgb (RGB reflectance, per channel), scalar_spectral (uniform reflectance on all
wavelengths), and llvm_ad_rgb and llvm_ad_spectral, where the plugin is traced inside a
symbolic loop (`dr.syntax` `while`, Dr.Jit's default mode)."""

import drjit as dr
import mitsuba as mi
import numpy as np
import pytest
from conftest import CONFIGS, config_id, kernel_f, random_pairs

RGB = [0.8, 0.5, 0.2]
N = 10_000


def compare(plugin_f, kernel, label):
    above = np.isfinite(plugin_f)
    err = np.abs(plugin_f - kernel) / np.maximum(np.abs(kernel), 1e-6)
    k = int(np.argmax(err))
    assert err.max() <= 1e-5, f"{label}: pair {k}: plugin {plugin_f[k]} vs kernel {kernel[k]}"
    assert above.all()


def plugin_eval_scalar(mi, bsdf, wi, wo, channels):
    ctx = mi.BSDFContext()
    out = np.zeros((len(wi), channels))
    si = mi.SurfaceInteraction3f()
    if channels == 4:
        si.wavelengths = mi.Spectrum([400, 500, 600, 700])
    for k in range(len(wi)):
        si.wi = mi.Vector3f(*wi[k])
        out[k] = np.array(bsdf.eval(ctx, si, mi.Vector3f(*wo[k])))
    return out


def divide_cos(values, wo):
    cos = wo[:, 2].astype(np.float64)
    safe = np.where(cos > 0, cos, 1.0)
    return np.where(cos[:, None] > 0, values / safe[:, None], 0.0)


@pytest.mark.parametrize("cfg", CONFIGS, ids=config_id)
@pytest.mark.parametrize("mi_variant", ["scalar_rgb"], indirect=True)
def test_scalar_rgb(mi_variant, cfg):
    mi = mi_variant
    kind, params = cfg
    bsdf = mi.load_dict({"type": kind, "reflectance": {"type": "rgb", "value": RGB}, **params})
    wi, wo = random_pairs(N, seed=21)
    f = divide_cos(plugin_eval_scalar(mi, bsdf, wi, wo, 3), wo)
    for c, rho in enumerate(RGB):
        compare(f[:, c], kernel_f(kind, params, rho, wi, wo), f"{kind} channel {c}")


@pytest.mark.parametrize("cfg", CONFIGS, ids=config_id)
@pytest.mark.parametrize("mi_variant", ["scalar_spectral"], indirect=True)
def test_scalar_spectral(mi_variant, cfg):
    mi = mi_variant
    kind, params = cfg
    bsdf = mi.load_dict({"type": kind, "reflectance": 0.7, **params})
    wi, wo = random_pairs(N, seed=22)
    f = divide_cos(plugin_eval_scalar(mi, bsdf, wi, wo, 4), wo)
    kernel = kernel_f(kind, params, 0.7, wi, wo)
    for c in range(4):
        compare(f[:, c], kernel, f"{kind} wavelength {c}")


@dr.syntax
def eval_in_symbolic_loop(bsdf, si, wo):
    """`bsdf.eval` recorded inside a symbolic `while` loop (one iteration). `dr.syntax`
    re-compiles the function from its source in the module's globals: no closures."""
    value = dr.zeros(mi.Spectrum, dr.width(wo))
    i = dr.zeros(mi.UInt32, dr.width(wo))
    while i < 1:
        value = bsdf.eval(mi.BSDFContext(), si, wo)
        i += 1
    return value


@pytest.mark.parametrize("cfg", CONFIGS, ids=config_id)
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb", "llvm_ad_spectral"], indirect=True)
def test_llvm_symbolic(mi_variant, cfg):
    assert mi_variant.variant() == mi.variant()
    kind, params = cfg
    spectral = mi.variant().endswith("spectral")
    rho = 0.7 if spectral else {"type": "rgb", "value": RGB}
    bsdf = mi.load_dict({"type": kind, "reflectance": rho, **params})
    wi, wo = random_pairs(N, seed=23)
    si = dr.zeros(mi.SurfaceInteraction3f, N)
    si.wi = mi.Vector3f(wi[:, 0], wi[:, 1], wi[:, 2])
    if spectral:
        si.wavelengths = mi.Spectrum(400, 500, 600, 700)
    value = eval_in_symbolic_loop(bsdf, si, mi.Vector3f(wo[:, 0], wo[:, 1], wo[:, 2]))
    f = divide_cos(np.array(value).T, wo)  # Color3f/Spectrum of width N -> (channels, N)
    if spectral:
        kernel = kernel_f(kind, params, 0.7, wi, wo)
        for c in range(4):
            compare(f[:, c], kernel, f"{kind} wavelength {c}")
    else:
        for c, r in enumerate(RGB):
            compare(f[:, c], kernel_f(kind, params, r, wi, wo), f"{kind} channel {c}")


@pytest.mark.parametrize("fast", [False, True])
@pytest.mark.parametrize("mi_variant", ["scalar_rgb", "llvm_ad_rgb"], indirect=True)
def test_roughdiffuse_is_oren_nayar_with_sigma_alpha_over_sqrt2(mi_variant, fast):
    """Mitsuba 0.6's conversion: `roughdiffuse` with alpha = a evaluates as `oren_nayar` with
    sigma = a/√2, full model (qualitative with use_fast_approx)."""
    assert mi_variant.variant() == mi.variant()
    a = 0.45
    rd = mi.load_dict({"type": "roughdiffuse", "alpha": a, "use_fast_approx": fast, "reflectance": 0.7})
    on = mi.load_dict(
        {"type": "oren_nayar", "sigma": a / np.sqrt(2), "model": "qualitative" if fast else "full", "reflectance": 0.7}
    )
    wi, wo = random_pairs(2000 if mi.variant().startswith("scalar") else N, seed=31)
    if mi.variant().startswith("scalar"):
        x = plugin_eval_scalar(mi, rd, wi, wo, 3)
        y = plugin_eval_scalar(mi, on, wi, wo, 3)
    else:
        si = dr.zeros(mi.SurfaceInteraction3f, len(wi))
        si.wi = mi.Vector3f(wi[:, 0], wi[:, 1], wi[:, 2])
        w = mi.Vector3f(wo[:, 0], wo[:, 1], wo[:, 2])
        x, y = np.array(eval_in_symbolic_loop(rd, si, w)), np.array(eval_in_symbolic_loop(on, si, w))
    assert np.abs(x).max() > 0.1
    np.testing.assert_allclose(x, y, rtol=2e-6, atol=1e-9)
