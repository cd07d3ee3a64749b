"""`<bsdf type="tabulated_brdf">` in the Mitsuba plugin (`docs/plugins.md#tabulated_brdf`):
its values in the scalar variant and traced in symbolic llvm against the table's multilinear
interpolation computed here in f64 numpy from the file's nodes (independent of matte's code),
with a reflectance that varies per lane and crosses the reflectance nodes; the gradient with
respect to the reflectance against central differences; Mitsuba's χ² test of the sampling; no
NaN at grazing, normal, coincident and below-horizon directions; file errors as one line
naming the file. The render gradient is in `test_gradients.py`, plugin against renderer in
`matte validate` (`mitsuba_scenes/sphere_tabulated_brdf.xml`). The values are checked on every
table in `python/matte_mitsuba/ground_truth/`, the rest on the V-cavities at σ = 0.3; the installed package
ships the same files (`matte_mitsuba.ground_truth_path`)."""

import glob
import json
import os

import drjit as dr
import numpy as np
import pytest
from conftest import REPO, random_pairs

GROUND_TRUTH = os.path.join(REPO, "python", "matte_mitsuba", "ground_truth")
TABLE = os.path.join(GROUND_TRUTH, "v_cavities_sigma0.3.json")
TABLES = sorted(glob.glob(os.path.join(GROUND_TRUTH, "*.json")))
VARIANTS = ["scalar_rgb", "llvm_ad_rgb"]


def reference_f(table, wi, wo, rho):
    """f (no cosine) by the file format's definition (docs/microgeometry.md#file-format), f64:
    θ = acos z in degrees, Δφ the angle between the directions' projections (0 when either
    is the normal), multilinear in (ρ, θi, θo, Δφ) between the nodes, clamped at the ends.
    `wi`, `wo`: (n, 3); `rho`: (n, c). Zero unless both directions are above."""
    theta = np.array(table["theta_deg"])
    phi = np.array(table["delta_phi_deg"])
    refl = np.array(table["reflectance"])
    values = np.array(table["f_over_reflectance"], dtype=np.float64).reshape(
        len(refl), len(theta), len(theta), len(phi)
    )
    wi, wo = wi.astype(np.float64), wo.astype(np.float64)

    def locate(nodes, x):
        if len(nodes) == 1:
            return np.zeros_like(x, dtype=int), np.zeros_like(x), np.zeros_like(x, dtype=int)
        xc = np.clip(x, nodes[0], nodes[-1])
        k = np.clip(np.searchsorted(nodes, xc, side="right") - 1, 0, len(nodes) - 2)
        return k, (xc - nodes[k]) / (nodes[k + 1] - nodes[k]), k + 1

    ti = np.degrees(np.arccos(np.clip(wi[:, 2], -1, 1)))
    to = np.degrees(np.arccos(np.clip(wo[:, 2], -1, 1)))
    la, lb = np.hypot(wi[:, 0], wi[:, 1]), np.hypot(wo[:, 0], wo[:, 1])
    cos_dp = (wi[:, 0] * wo[:, 0] + wi[:, 1] * wo[:, 1]) / np.maximum(la * lb, 1e-300)
    dp = np.where((la < 1e-7) | (lb < 1e-7), 0.0, np.degrees(np.arccos(np.clip(cos_dp, -1, 1))))
    (i0, wti, i1), (o0, wto, o1), (p0, wp, p1) = locate(theta, ti), locate(theta, to), locate(phi, dp)
    out = np.zeros(rho.shape)
    for c in range(rho.shape[1]):
        r0, wr, r1 = locate(refl, rho[:, c])
        total = 0.0
        for r, a in ((r0, 1 - wr), (r1, wr)):
            for i, b in ((i0, 1 - wti), (i1, wti)):
                for o, d in ((o0, 1 - wto), (o1, wto)):
                    for p, e in ((p0, 1 - wp), (p1, wp)):
                        total = total + a * b * d * e * values[r, i, o, p]
        out[:, c] = rho[:, c] * total
    above = (wi[:, 2] > 0) & (wo[:, 2] > 0)
    return np.where(above[:, None], out, 0.0)


def read(path):
    with open(path) as f:
        return json.load(f)


@pytest.fixture(scope="module")
def table():
    return read(TABLE)


def load(mi, reflectance, path=TABLE):
    return mi.load_dict({"type": "tabulated_brdf", "filename": path, "reflectance": reflectance})


def interactions(mi, wi, uv):
    n = len(wi)
    si = dr.zeros(mi.SurfaceInteraction3f, n)
    si.wi = mi.Vector3f(*[wi[:, k] for k in range(3)])
    si.uv = mi.Point2f(uv[:, 0], uv[:, 1])
    return si


def evaluate(mi, bsdf, wi, wo, uv):
    """(f·cos θo, pdf, reflectance) per pair: one vectorised call in the JIT variants, a loop in
    the scalar ones."""
    ctx = mi.BSDFContext()
    if mi.variant().startswith("scalar"):
        rows = []
        for a, b, t in zip(wi, wo, uv):
            si = dr.zeros(mi.SurfaceInteraction3f)
            si.wi, si.uv = mi.Vector3f(*map(float, a)), mi.Point2f(*map(float, t))
            v, pdf = bsdf.eval_pdf(ctx, si, mi.Vector3f(*map(float, b)))
            rows.append((list(v), pdf, list(bsdf.eval_diffuse_reflectance(si))))
        return (np.array([r[0] for r in rows]), np.array([r[1] for r in rows]), np.array([r[2] for r in rows]))
    si = interactions(mi, wi, uv)
    v, pdf = bsdf.eval_pdf(ctx, si, mi.Vector3f(*[wo[:, k] for k in range(3)]))
    rho = bsdf.eval_diffuse_reflectance(si)
    return np.array(v).reshape(3, -1).T, np.array(pdf).ravel(), np.array(rho).reshape(3, -1).T


def lane_reflectance(mi):
    """A 4×4 bitmap of reflectances from 0 to 1 (nearest filtering): each lane's ρ per channel
    differs, covering every reflectance cell and both end nodes."""
    rng = np.random.default_rng(5)
    data = rng.uniform(0.0, 1.0, (4, 4, 3)).astype(np.float32)
    data[0, 0] = (0.0, 1.0, 0.5)
    return {"type": "bitmap", "bitmap": mi.Bitmap(data), "filter_type": "nearest", "raw": True}


@pytest.mark.parametrize("path", TABLES, ids=os.path.basename)
@pytest.mark.parametrize("mi_variant", VARIANTS, indirect=True)
def test_values_equal_the_tables_interpolation(mi_variant, path):
    mi = mi_variant
    table = read(path)
    n = 4000 if mi.variant().startswith("scalar") else 100_000
    wi, wo = random_pairs(n, seed=17)
    uv = np.random.default_rng(3).uniform(0, 1, (n, 2)).astype(np.float32)
    bsdf = load(mi, lane_reflectance(mi), path)
    value, pdf, rho = evaluate(mi, bsdf, wi, wo, uv)
    assert np.all(np.isfinite(value)) and np.all(np.isfinite(pdf))
    assert len(np.unique(np.round(rho[:, 0], 4))) >= 10, "the reflectance does not vary per lane"
    want = reference_f(table, wi, wo, rho) * np.maximum(wo[:, 2:3].astype(np.float64), 0)
    # Relative to ρ · cos θo · the table's largest value: f32 angles move the interpolation
    # weights by a few 1e-6 of a cell (tests/kernels/tabulated_brdf.rs).
    scale = max(table["f_over_reflectance"]) * np.maximum(rho, 1e-3) * np.maximum(wo[:, 2:3], 1e-3)
    gap = np.abs(value - want) / scale
    print(f"{mi.variant()}: largest difference {gap.max():.2e} of ρ·cos θo·max f/ρ")
    assert gap.max() < 1e-5, (gap.max(), np.unravel_index(np.argmax(gap), gap.shape))
    above = (wi[:, 2] > 0) & (wo[:, 2] > 0)
    assert np.allclose(pdf, np.where(above, wo[:, 2] / np.pi, 0), rtol=1e-5, atol=1e-7)
    assert np.count_nonzero(want[above]) > 0.9 * want[above].size  # not a comparison of zeros


@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_reflectance_gradient_equals_central_differences(mi_variant):
    """d/dρ of Σ eval over 10⁴ pairs, per channel, by autodiff through the traced interpolation
    against central differences (ρ ± 1e-2 stays inside a reflectance cell, where f is
    quadratic in ρ, so the difference is exact up to rounding)."""
    mi = mi_variant
    n = 10_000
    wi, wo = random_pairs(n, seed=23)
    base = [0.35, 0.6, 0.85]
    bsdf = load(mi, {"type": "rgb", "value": base})
    params = mi.traverse(bsdf)
    key = "reflectance.value"
    si = interactions(mi, wi, np.zeros((n, 2), np.float32))
    wo_ = mi.Vector3f(*[wo[:, k] for k in range(3)])

    def total(rho):
        params[key] = mi.Color3f(*rho)
        params.update()
        return bsdf.eval(mi.BSDFContext(), si, wo_)

    for c in range(3):
        rho = mi.Color3f(*base)
        dr.enable_grad(rho)
        params[key] = rho
        params.update()
        v = bsdf.eval(mi.BSDFContext(), si, wo_)
        dr.backward(dr.sum(v[c], axis=None))
        ad = float(dr.grad(rho)[c][0])
        h = 1e-2
        up, down = list(base), list(base)
        up[c] += h
        down[c] -= h
        fd = (float(dr.sum(total(up)[c], axis=None)[0]) - float(dr.sum(total(down)[c], axis=None)[0])) / (2 * h)
        print(f"channel {c}: AD {ad:.7g}  FD {fd:.7g}  relative gap {abs(ad - fd) / abs(fd):.1e}")
        assert np.isfinite(ad) and fd > 0
        assert abs(ad - fd) <= 0.01 * abs(fd), (c, ad, fd)


@pytest.mark.parametrize("theta", [0.0, 45.0, 85.0, 89.5])
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)  # mitsuba.chi2 needs a JIT variant
def test_chi2(mi_variant, theta):
    mi = mi_variant
    t = np.radians(theta)
    sample_func, pdf_func = mi.chi2.BSDFAdapter(
        "tabulated_brdf", f'<string name="filename" value="{TABLE}"/>', wi=[float(np.sin(t)), 0.0, float(np.cos(t))]
    )
    chi2 = mi.chi2.ChiSquareTest(
        domain=mi.chi2.SphericalDomain(), sample_func=sample_func, pdf_func=pdf_func, sample_dim=3
    )
    assert chi2.run(test_count=8), chi2.messages


@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_no_nan_at_special_directions_with_gradients(mi_variant):
    """Grazing, normal, coincident, opposite and below-horizon directions: values, pdf, sample
    weights and the reflectance gradient are finite."""
    mi = mi_variant
    d = [
        (0, 0, 1),
        (1, 0, 0),
        (1, 0, 1e-7),
        (0.6, 0, 0.8),
        (-0.6, 0, 0.8),
        (0, 0.6, 0.8),
        (0.6, 0, -0.8),
        (1e-8, 0, 1),
        (0, 0, -1),
        (0.7071068, 0.7071068, 0),
    ]
    pairs = [(a, b) for a in d for b in d]
    wi = np.array([p[0] for p in pairs], np.float32)
    wo = np.array([p[1] for p in pairs], np.float32)
    bsdf = load(mi, {"type": "rgb", "value": [0.0, 0.5, 1.0]})
    params = mi.traverse(bsdf)
    rho = mi.Color3f(params["reflectance.value"])
    dr.enable_grad(rho)
    params["reflectance.value"] = rho
    params.update()
    si = interactions(mi, wi, np.zeros((len(wi), 2), np.float32))
    v, pdf = bsdf.eval_pdf(mi.BSDFContext(), si, mi.Vector3f(*[wo[:, k] for k in range(3)]))
    bs, w = bsdf.sample(mi.BSDFContext(), si, 0.5, mi.Point2f(0.3, 0.9))
    dr.backward(dr.sum(v[0] + v[1] + v[2] + w[0] + w[1] + w[2], axis=None))
    for x in (v, pdf, w, bs.wo, bs.pdf, dr.grad(rho)):
        assert np.all(np.isfinite(np.array(x))), x


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return str(path)


@pytest.mark.parametrize("mi_variant", VARIANTS, indirect=True)
def test_file_errors_are_one_line_naming_the_file(mi_variant, tmp_path, table):
    mi = mi_variant
    wrong_version = dict(table, version=99)
    wrong_format = dict(table, format="something-else")
    short = dict(table, f_over_reflectance=table["f_over_reflectance"][:-1])
    cases = {
        str(tmp_path / "missing_table.json"): "No such file",
        write(
            tmp_path / "malformed.json", '{"format": "matte-tabulated-brdf",\n "version": 1,\n "oops"'
        ): "malformed.json:3",
        write(tmp_path / "version.json", json.dumps(wrong_version)): "version 99",
        write(tmp_path / "format.json", json.dumps(wrong_format)): "something-else",
        write(tmp_path / "short.json", json.dumps(short)): "f_over_reflectance",
    }
    for path, needle in cases.items():
        with pytest.raises(Exception) as e:
            mi.load_dict({"type": "tabulated_brdf", "filename": path})
        msg = str(e.value)
        assert "\n" not in msg and os.path.basename(path) in msg and needle in msg, msg
        assert 'bsdf "tabulated_brdf": parameter "filename"' in msg, msg
    with pytest.raises(Exception) as e:
        mi.load_dict({"type": "tabulated_brdf"})
    assert 'parameter "filename": is missing' in str(e.value) and "\n" not in str(e.value)
    with pytest.raises(Exception) as e:
        mi.load_dict({"type": "tabulated_brdf", "filename": TABLE, "sigma": 0.3})
    assert 'parameter "sigma": unknown parameter' in str(e.value)


def test_the_package_ships_every_table():
    import matte_mitsuba

    names = sorted(os.path.basename(p) for p in TABLES)
    assert sorted(f for f in os.listdir(matte_mitsuba.GROUND_TRUTH) if f.endswith(".json")) == names
    for name in names:
        with (
            open(os.path.join(GROUND_TRUTH, name), "rb") as a,
            open(matte_mitsuba.ground_truth_path(name[:-5]), "rb") as b,
        ):
            assert a.read() == b.read(), f"the installed {name} differs from the checkout's (make plugin)"
    with pytest.raises(ValueError, match="no ground-truth table 'v_cavities_sigma9'.*v_cavities_sigma0.3"):
        matte_mitsuba.ground_truth_path("v_cavities_sigma9")
