"""No NaN or Inf from the traced kernels, in values or in gradients, over 10^6 direction pairs
that include grazing, below-horizon, normal-incidence and coincident directions: masked lanes
must stay finite, since autodiff multiplies a discarded lane's NaN by a zero adjoint and gets
NaN. The parameters' gradients sum over all lanes, so one bad lane shows."""

import drjit as dr
import mitsuba as mi
import numpy as np
import pytest
from conftest import CONFIGS, config_id

N = 1_000_000


def directions(rng, n):
    z = rng.uniform(-1, 1, n)
    # a tenth of each: exactly grazing, within 1e-7 of the horizon (both sides), the normal
    k = n // 10
    z[:k] = 0.0
    z[k : 2 * k] = rng.choice([-1e-7, 1e-7, 1e-30, 0.0], k)
    z[2 * k : 3 * k] = 1.0
    phi = rng.uniform(0, 2 * np.pi, n)
    r = np.sqrt(np.maximum(0.0, 1 - z * z))
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1).astype(np.float32)


@pytest.mark.parametrize("cfg", CONFIGS, ids=config_id)
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_values_and_gradients_are_finite(mi_variant, cfg):
    assert mi_variant.variant() == mi.variant()
    kind, params = cfg
    bsdf = mi.load_dict({"type": kind, "reflectance": {"type": "rgb", "value": [0.8, 0.5, 0.2]}, **params})
    p = mi.traverse(bsdf)
    keys = list(p.keys())
    for k in keys:
        dr.enable_grad(p[k])
    p.update()
    rng = np.random.default_rng(5)
    wi, wo = directions(rng, N), directions(rng, N)
    wo[N - N // 10 :] = wi[N - N // 10 :]  # coincident pairs
    u = rng.uniform(0, 1, (N, 3)).astype(np.float32)
    u[: N // 20, 1:] = rng.choice([0.0, 0.5, np.nextafter(np.float32(1), np.float32(0))], (N // 20, 2))
    si = dr.zeros(mi.SurfaceInteraction3f, N)
    si.wi = mi.Vector3f(wi[:, 0], wi[:, 1], wi[:, 2])
    ctx = mi.BSDFContext()
    value, pdf = bsdf.eval_pdf(ctx, si, mi.Vector3f(wo[:, 0], wo[:, 1], wo[:, 2]))
    bs, weight = bsdf.sample(ctx, si, mi.Float(u[:, 0]), mi.Point2f(u[:, 1], u[:, 2]))
    loss = dr.sum(value, axis=None) + dr.sum(weight, axis=None) + dr.sum(pdf) + dr.sum(bs.pdf)
    dr.backward(loss)
    for name, x in (("value", value), ("pdf", pdf), ("weight", weight), ("sampled pdf", bs.pdf), ("wo", bs.wo)):
        a = np.array(dr.detach(x))
        assert np.isfinite(a).all(), f"{name}: {np.count_nonzero(~np.isfinite(a))} non-finite lanes"
    for k in keys:
        g = np.array(dr.grad(p[k]))
        assert np.isfinite(g).all(), f"gradient of {k}: {g}"
        assert np.any(g != 0), f"gradient of {k} is zero"
