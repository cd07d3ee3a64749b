"""Gradients through the traced kernels: d(image mean)/d(parameter) by Mitsuba's `prb`
(automatic differentiation, adjoint pass with the primal's seed, so it is the exact derivative
of what finite differences measure) against central finite differences of renders with the
same seed, for every differentiable parameter of every type, within 1 %. For `reflectance`
the derivative is along (1, 1, 1) (all channels together).

Where a model's sampler depends on a parameter (EON's `sampling="cltc"` on the roughness),
same-seed finite differences also move the sampled directions, so they are the derivative of
another estimator: there the 1 % check runs with the cosine, and the own sampler's adjoint,
averaged over seeds, must equal the cosine's within its Monte Carlo error (the expected image
does not depend on the sampler)."""

import os

import drjit as dr
import numpy as np
import pytest
from conftest import REPO
from matte_mitsuba import registry
from matte_mitsuba.gradient_check import adjoint_gradient, central_difference, shifted

RES, SPP, SEED = 24, 8, 3

# (type, fixed parameters, {differentiable parameter: finite-difference step})
CASES = [
    ("diffuse", {}, {"reflectance.value": 1e-2}),
    ("lambert", {}, {"reflectance.value": 1e-2}),
    ("oren_nayar", {"sigma": 0.5}, {"reflectance.value": 1e-2, "sigma": 1e-2}),
    ("oren_nayar", {"sigma": 0.5, "model": "full"}, {"reflectance.value": 1e-2, "sigma": 1e-2}),
    ("eon", {"roughness": 0.5}, {"reflectance.value": 1e-2, "roughness": 1e-2}),
    ("eon", {"roughness": 0.5, "sampling": "cltc"}, {"reflectance.value": 1e-2}),
    ("wolff", {"int_ior": 1.5, "ext_ior": 1.1}, {"reflectance.value": 1e-2, "int_ior": 1e-2, "ext_ior": 1e-2}),
    ("wolff", {"int_ior": 1.5, "normalization": "normal"}, {"int_ior": 1e-2}),
    ("wolff", {"int_ior": 1.5, "normalization": "raw"}, {"int_ior": 1e-2}),
    ("ginneken", {"roughness": 0.4}, {"reflectance.value": 1e-2, "roughness": 4e-3}),
    ("ginneken", {"roughness": 0.4, "shadowing": "height_correlated"}, {"roughness": 4e-3}),
    # The white walls' reflectance (0.885, 0.698, 0.666) ± 1e-2 stays inside the table's cells.
    (
        "tabulated_brdf",
        {"filename": os.path.join(REPO, "python", "matte_mitsuba", "ground_truth", "v_cavities_sigma0.3.json")},
        {"reflectance.value": 1e-2},
    ),
]
# Every other registered model at its defaults: reflectance and each numeric parameter.
CASES += [
    (
        m["name"],
        {},
        {"reflectance.value": 1e-2, **{p["name"]: 1e-2 for p in registry.numeric_parameters(m)}},
    )
    for m in registry.MODELS
    if m["name"] not in {c[0] for c in CASES}
]


def case_id(case):
    kind, fixed, _ = case
    return kind + "".join(f"-{k}={os.path.basename(str(v))}" for k, v in fixed.items())


def cornell(mi, kind, fixed):
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = RES
    d["integrator"] = {"type": "prb", "max_depth": 4, "rr_depth": 1000}  # no roulette: smooth in the parameters
    for name in ("white", "red", "green"):
        d[name]["type"] = kind
        d[name].update(fixed)
    return mi.load_dict(d)


@pytest.mark.parametrize("case", CASES, ids=case_id)
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_ad_matches_finite_differences(mi_variant, case):
    mi = mi_variant
    kind, fixed, steps = case
    scene = cornell(mi, kind, fixed)
    params = mi.traverse(scene)
    for name, h in steps.items():
        key = "white." + name
        assert key in params, sorted(k for k in params.keys() if k.startswith("white"))
        with_value = shifted(mi, params, key)
        params[key] = with_value(0.0)
        # Along (1, 1, 1) for a colour: the sum over its channels.
        ad = float(np.sum(adjoint_gradient(mi, scene, params, key, SPP, SEED)))
        fd = central_difference(mi, scene, params, key, with_value, h, SPP, SEED)
        print(f"{case_id(case)} d(mean)/d({name}): AD {ad:.7g}  FD {fd:.7g}  relative gap {abs(ad - fd) / abs(fd):.1e}")
        assert np.isfinite(ad) and abs(fd) > 1e-6, (ad, fd)
        assert abs(ad - fd) <= 0.01 * abs(fd), f"{name}: AD {ad} vs FD {fd}"


# Models with their own sampler: each numeric parameter, the adjoint with the own sampler
# against the cosine-sampled one (checked against finite differences above).
OWN = [
    (m["name"], p["name"], s)
    for m in registry.MODELS
    for s in registry.own_samplers(m)
    for p in registry.numeric_parameters(m)
]


@pytest.mark.parametrize("kind,name,own", OWN)
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_own_sampler_gradient_equals_the_cosine_samplers(mi_variant, kind, name, own):
    mi = mi_variant
    seeds, spp = range(8), 64
    key = "white." + name
    means = {}
    for sampling in (own, "cosine"):
        scene = cornell(mi, kind, {name: 0.5, "sampling": sampling})
        params = mi.traverse(scene)
        g = []
        for seed in seeds:
            dr.clear_grad(params[key])  # the adjoint pass accumulates
            g.append(float(np.sum(adjoint_gradient(mi, scene, params, key, spp, seed))))
        means[sampling] = (np.mean(g), np.std(g, ddof=1) / np.sqrt(len(g)))
    (a, sa), (b, sb) = means[own], means["cosine"]
    print(f"{kind} d(mean)/d({name}): own sampler {a:.6g} ± {sa:.2g}, cosine {b:.6g} ± {sb:.2g}")
    assert abs(a - b) <= 0.01 * abs(b) + 3 * np.hypot(sa, sb), (a, sa, b, sb)
    assert 3 * np.hypot(sa, sb) < 0.05 * abs(b), "too noisy to tell"
