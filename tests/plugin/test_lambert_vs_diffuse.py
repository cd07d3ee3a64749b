"""`lambert` against Mitsuba's built-in `diffuse`: same eval, pdf and sample (same sample
inputs) to 1e-6 relative, and the same Cornell box image with the same seed to 1e-5."""

import numpy as np
import pytest
from conftest import random_pairs


def cornell_render(mi, kind, res, spp, seed):
    """mi.cornell_box() at res², every material of type `kind`, rendered with `seed`."""
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = res
    for name in ("white", "red", "green"):
        d[name]["type"] = kind
    return np.array(mi.render(mi.load_dict(d), spp=spp, seed=seed))


@pytest.mark.parametrize("mi_variant", ["scalar_rgb"], indirect=True)
def test_eval_pdf_sample_match_diffuse(mi_variant):
    mi = mi_variant
    refl = {"type": "rgb", "value": [0.8, 0.5, 0.2]}
    ours = mi.load_dict({"type": "lambert", "reflectance": refl})
    theirs = mi.load_dict({"type": "diffuse", "reflectance": refl})
    ctx = mi.BSDFContext()
    wi, wo = random_pairs(10_000, seed=11)
    rng = np.random.default_rng(12)
    u = rng.random((10_000, 3), dtype=np.float32)
    worst = 0.0
    for k in range(len(wi)):
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(*wi[k])
        w = mi.Vector3f(*wo[k])
        pairs = [
            (np.array(ours.eval(ctx, si, w)), np.array(theirs.eval(ctx, si, w))),
            (np.array([ours.pdf(ctx, si, w)]), np.array([theirs.pdf(ctx, si, w)])),
        ]
        (bs_a, w_a), (bs_b, w_b) = ours.sample(ctx, si, u[k, 0], u[k, 1:]), theirs.sample(ctx, si, u[k, 0], u[k, 1:])
        pairs += [
            (np.array(w_a), np.array(w_b)),
            (np.array(bs_a.wo), np.array(bs_b.wo)),
            (np.array([bs_a.pdf]), np.array([bs_b.pdf])),
        ]
        for a, b in pairs:
            err = np.max(np.abs(a - b) / np.maximum(np.abs(b), 1e-3))
            worst = max(worst, err)
            assert err <= 1e-6, f"pair {k}: {a} vs {b} (wi={wi[k]}, wo={wo[k]}, u={u[k]})"
    print(f"max relative difference lambert vs diffuse: {worst:.2e}")


@pytest.mark.parametrize("mi_variant", ["scalar_rgb", "llvm_ad_rgb"], indirect=True)
def test_cornell_box_render_matches_diffuse(mi_variant):
    mi = mi_variant

    ref, img = cornell_render(mi, "diffuse", 64, 16, 7), cornell_render(mi, "lambert", 64, 16, 7)
    assert np.isfinite(img).all()
    diff = np.abs(img - ref).max()
    print(f"{mi.variant()}: max |lambert - diffuse| = {diff:.2e} (mean {ref.mean():.4f})")
    assert diff <= 1e-5


@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_symbolic_render_is_bit_identical_to_diffuse_with_one_thread(mi_variant):
    """Traced `lambert` records the operations of `diffuse` (ρ·(1/π)·cos θo, weight ρ, the same
    warp): with one LLVM thread (film accumulation order fixed) the images are identical."""
    mi = mi_variant
    import drjit as dr

    threads = dr.thread_count()
    dr.set_thread_count(1)
    try:
        ref, img = cornell_render(mi, "diffuse", 48, 8, 3), cornell_render(mi, "lambert", 48, 8, 3)
    finally:
        dr.set_thread_count(threads)
    assert ref.mean() > 0.05
    assert np.array_equal(img, ref), f"max |lambert - diffuse| = {np.abs(img - ref).max():.2e}"
