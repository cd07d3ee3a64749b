"""`burley` against Mitsuba's own `principled` with every lobe but the diffuse one off
(metallic, specular, spec_trans, sheen, clearcoat and flatness 0): its diffuse and
retro-reflection terms are Burley's diffuse (`src/bsdfs/principled.cpp`, written with the half
vector normalised). Eval (f·cos θo) to 2e-6 relative on 4000 pairs, for several roughnesses,
in scalar_rgb and traced in llvm_ad_rgb; a textured roughness as the float."""

import numpy as np
import pytest
from conftest import random_pairs

ROUGHNESS = [0.0, 0.3, 1.0]


def both(mi, r, rho=(0.8, 0.5, 0.2)):
    refl = {"type": "rgb", "value": list(rho)}
    ours = mi.load_dict({"type": "burley", "reflectance": refl, "roughness": r})
    theirs = mi.load_dict(
        {
            "type": "principled",
            "base_color": refl,
            "roughness": r,
            "metallic": 0.0,
            "specular": 0.0,
            "spec_trans": 0.0,
            "sheen": 0.0,
            "clearcoat": 0.0,
            "flatness": 0.0,
        }
    )
    return ours, theirs


def eval_all(mi, bsdf, wi, wo):
    ctx = mi.BSDFContext()
    if mi.variant().startswith("scalar"):
        out = []
        for a, b in zip(wi, wo):
            si = mi.SurfaceInteraction3f()
            si.wi = mi.Vector3f(*a)
            out.append(np.array(bsdf.eval(ctx, si, mi.Vector3f(*b))))
        return np.array(out)
    si = dr_si(mi, wi)
    return np.array(bsdf.eval(ctx, si, mi.Vector3f(wo[:, 0], wo[:, 1], wo[:, 2]))).T


def dr_si(mi, wi):
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(wi[:, 0], wi[:, 1], wi[:, 2])
    return si


@pytest.mark.parametrize("r", ROUGHNESS)
@pytest.mark.parametrize("mi_variant", ["scalar_rgb", "llvm_ad_rgb"], indirect=True)
def test_eval_matches_principled_diffuse_lobe(mi_variant, r):
    mi = mi_variant
    n = 1000 if mi.variant().startswith("scalar") else 4000
    wi, wo = random_pairs(n, seed=21)
    above = (wi[:, 2] > 1e-3) & (wo[:, 2] > 1e-3)
    wi, wo = wi[above], wo[above]
    ours, theirs = both(mi, r)
    a, b = eval_all(mi, ours, wi, wo), eval_all(mi, theirs, wi, wo)
    assert np.isfinite(a).all()
    assert (b > 0).all()
    err = np.max(np.abs(a - b) / b)
    print(f"{mi.variant()} r={r}: max relative difference burley vs principled {err:.2e}")
    assert err <= 2e-6


@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_below_the_surface_is_zero_as_principled(mi_variant):
    mi = mi_variant
    wi, wo = random_pairs(4000, seed=22)
    below = (wi[:, 2] <= 0) | (wo[:, 2] <= 0)
    ours, theirs = both(mi, 0.5)
    a, b = eval_all(mi, ours, wi[below], wo[below]), eval_all(mi, theirs, wi[below], wo[below])
    assert below.sum() > 100
    assert (a == 0).all() and (b == 0).all()
