"""The models' own importance samplers in the plugin (`docs/sampling.md`): Mitsuba's
`mitsuba.chi2.ChiSquareTest` at several roughnesses and at incidences down to 89°, in the
scalar variant and symbolic llvm; the density the sampler returns equals `pdf()` at the
sampled direction; and a roughness texture samples as the number it stands for."""

import drjit as dr
import numpy as np
import pytest
from matte_mitsuba import registry

# Every model that offers a sampler besides the cosine, with it, at two roughnesses (its first
# numeric parameter, as the registry declares it).
OWN = [(m, s) for m in registry.MODELS for s in registry.own_samplers(m)]
CASES = [(m["name"], {registry.numeric_parameters(m)[0]["name"]: r, "sampling": s}) for m, s in OWN for r in (0.3, 1.0)]
ANGLES = [30.0, 85.0, 89.0]


def case_id(case):
    kind, params = case
    return kind + "".join(f"-{k}={v}" for k, v in params.items())


def direction(theta_deg):
    t = np.radians(theta_deg)
    return [float(np.sin(t)), 0.0, float(np.cos(t))]


def test_some_model_has_its_own_sampler():
    assert CASES, "no registered model offers a sampler other than the cosine"


@pytest.mark.parametrize("theta", ANGLES)
@pytest.mark.parametrize("case", CASES, ids=case_id)
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_chi2(mi_variant, case, theta):
    mi = mi_variant
    kind, params = case
    xml = "".join(
        f'<float name="{k}" value="{v}"/>' if isinstance(v, float) else f'<string name="{k}" value="{v}"/>'
        for k, v in params.items()
    )
    sample_func, pdf_func = mi.chi2.BSDFAdapter(kind, xml, wi=direction(theta))
    chi2 = mi.chi2.ChiSquareTest(
        domain=mi.chi2.SphericalDomain(), sample_func=sample_func, pdf_func=pdf_func, sample_dim=3
    )
    assert chi2.run(test_count=len(CASES) * len(ANGLES)), chi2.messages


@pytest.mark.parametrize("case", CASES, ids=case_id)
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_sampled_pdf_is_pdf(mi_variant, case):
    mi = mi_variant
    kind, params = case
    n = 100_000
    rng = np.random.default_rng(11)
    z = rng.uniform(1e-4, 1.0, n)
    phi = rng.uniform(0, 2 * np.pi, n)
    s = np.sqrt(1 - z * z)
    si = dr.zeros(mi.SurfaceInteraction3f, n)
    si.wi = mi.Vector3f(s * np.cos(phi), s * np.sin(phi), z)
    u = rng.uniform(0, 1, (n, 3))
    bsdf = mi.load_dict({"type": kind, **params})
    ctx = mi.BSDFContext()
    bs, _ = bsdf.sample(ctx, si, mi.Float(u[:, 0]), mi.Point2f(u[:, 1], u[:, 2]))
    a, b = np.array(bs.pdf), np.array(bsdf.pdf(ctx, si, bs.wo))
    ok = a > 0
    assert ok.mean() > 0.99
    assert np.allclose(a[ok], b[ok], rtol=1e-5, atol=0)
    # The sampler is the model's own, not the cosine.
    assert not np.allclose(a[ok], np.array(bs.wo.z)[ok] / np.pi, rtol=1e-3)


def draw(mi, kind, params, wi, u):
    """(wo, pdf) per row of `wi` and `u` (n × 3) in the current variant."""
    bsdf = mi.load_dict({"type": kind, **params})
    ctx = mi.BSDFContext()
    if mi.variant().startswith("scalar"):
        rows = []
        for k in range(len(wi)):
            si = mi.SurfaceInteraction3f()
            si.wi = mi.Vector3f(*map(float, wi[k]))
            bs, _ = bsdf.sample(ctx, si, float(u[k, 0]), mi.Point2f(float(u[k, 1]), float(u[k, 2])))
            rows.append([bs.wo.x, bs.wo.y, bs.wo.z, bs.pdf])
        out = np.array(rows, dtype=np.float64)
        return out[:, :3], out[:, 3]
    si = dr.zeros(mi.SurfaceInteraction3f, len(wi))
    si.wi = mi.Vector3f(wi[:, 0], wi[:, 1], wi[:, 2])
    bs, _ = bsdf.sample(ctx, si, mi.Float(u[:, 0]), mi.Point2f(u[:, 1], u[:, 2]))
    return np.array(bs.wo, dtype=np.float64).T, np.array(bs.pdf, dtype=np.float64)


@pytest.mark.parametrize("case", CASES, ids=case_id)
def test_scalar_and_llvm_draw_the_same_directions(case):
    import matte_mitsuba
    import mitsuba as mi

    kind, params = case
    n = 4000
    rng = np.random.default_rng(17)
    z = rng.uniform(1e-3, 1.0, n)
    phi = rng.uniform(0, 2 * np.pi, n)
    s = np.sqrt(1 - z * z)
    wi = np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=1).astype(np.float32)
    u = rng.uniform(0, 1, (n, 3)).astype(np.float32)
    got = {}
    for variant in ("scalar_rgb", "llvm_ad_rgb"):
        mi.set_variant(variant)
        matte_mitsuba.register()
        got[variant] = draw(mi, kind, params, wi, u)
    (wo_s, pdf_s), (wo_l, pdf_l) = got["scalar_rgb"], got["llvm_ad_rgb"]
    assert np.abs(wo_s - wo_l).max() < 1e-4, np.abs(wo_s - wo_l).max()
    # The directions agree to float rounding (scalar and LLVM round differently); where the
    # lobe is steep (grazing wo, roughness 1) that moves the density by up to ~2e-4.
    assert np.allclose(pdf_s, pdf_l, rtol=1e-3, atol=1e-7)
