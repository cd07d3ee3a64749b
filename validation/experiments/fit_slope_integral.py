"""Prototype representations of van Ginneken's slope integral I(θi, θo, Δφ; m) that keep the
6.2 MB table out of the hot path, measured the way `matte tables` measures the fast
path (`rust/brdf/src/models/ginneken/accuracy.rs`: relative error of f at 20,000 R3 configurations,
θi, θo ≤ 80° or 85°, Δφ ∈ [0°, 180°]). f = (ρ/π) I / (μi μo / P_ill+vis) and the visibility is
evaluated in closed form by every representation alike, so the relative error of f is that of I
(`--check-f` confirms it against the installed `matte brdf`).

    .venv/bin/python validation/experiments/fit_slope_integral.py [--samples 20000] [--sweep] [--textured] [--check-f]

Candidates:

* `current`   today's table: I on 80 × 80 × 32 nodes (x = √(1−μ)/(√(1−μ)+√μ), c = cos Δφ), trilinear.
* `residual`  I − I_unc (the closed-form unclamped part) on a small trilinear table, same axes.
* `split`     I = rest / (1 − r). `rest` is a sum of non-negative terms built from three 1-D
              functions of each direction (tabulated on 128 nodes of x, linear: 1.5 KB), `r = K/I`
              the share of the both-facing-away wedge K on a 16³ (16 KB) or 20³ (31 KB) trilinear
              table over v = m sin θ/(m sin θ + μ) per direction and Δφ (uniform in angle).

The decomposition (exact; `slope_reference.py` has the functions): with X the slope component
along a direction's azimuth, (μ − p·w)⁺ = (μ − p·w) + s (X − cot θ)⁺. Expanding the product of the
two clamped cosines gives the unclamped part, one one-clamp term per direction (1-D functions of
that direction: the other factor is linear in the slope, its component across X averages out)
and K = E[w (p·wi − μi)⁺ (p·wo − μo)⁺]. The unclamped and one-clamp terms together are linear in
cos Δφ; at Δφ = π (K = 0 there) they are the integral over the slab −cot θo < X < cot θi, which
splits at X = 0 into two one-direction pieces. Hence

    rest = μo P0(θi) + μi P0(θo) + so P1(θi) + si P1(θo) + (1 + cos Δφ) si so (H(θi) + H(θo))

with P0 = E[h (μ − sX); 0<X<cot θ], P1 = E[h X (μ − sX); 0<X<cot θ], H = E[h X min(X, cot θ); X>0],
h(X) = E_Z[1/√(1+X²+Z²)]: every term ≥ 0, so no cancellation (the naive I_unc + corrections
cancels by up to 100× in grazing forward scattering). P0/μ², P1/μ³ and H/μ are smooth and
non-zero on μ ∈ [0, 1]: those are tabulated.
"""

import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import slope_reference as sr  # noqa: E402

# ----------------------------------------------------------------------------- axes, lookups


def axis_of_cos(mu):
    a, b = np.sqrt(np.maximum(1 - mu, 0)), np.sqrt(np.maximum(mu, 0))
    return a / (a + b)


def cos_of_axis(x):
    y = 1 - x
    return y * y / (y * y + x * x)


def v_of_cos(mu, m):
    """Wedge-table axis v = 1/(1 + a), a = cot θ/m = μ/(m sin θ): 0 at the normal, 1 at grazing."""
    s = np.sqrt(np.maximum(1 - mu * mu, 0))
    return s * m / (s * m + mu)


def cos_of_v(v, m):
    v = np.asarray(v, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        ct = m * (1 - v) / v
        return np.where(v > 0, ct / np.sqrt(1 + ct * ct), 1.0)


def _cell(s, n):
    s = np.clip(s, 0, n - 1)
    lo = np.minimum(np.floor(s), n - 2)
    return lo.astype(int), s - lo


def trilinear(T, a, b, c):
    """T on nodes uniform in [0, 1]³, at (a, b, c) ∈ [0, 1]³."""
    ni, no, nc = T.shape
    (i, fi), (o, fo), (k, fc) = _cell(a * (ni - 1), ni), _cell(b * (no - 1), no), _cell(c * (nc - 1), nc)
    v = 0.0
    for da in (0, 1):
        for db in (0, 1):
            for dc in (0, 1):
                w = (fi if da else 1 - fi) * (fo if db else 1 - fo) * (fc if dc else 1 - fc)
                v = v + w * T[i + da, o + db, k + dc]
    return v


def linear1d(T, x):
    n = T.shape[-1]
    i, f = _cell(x * (n - 1), n)
    return T[..., i] * (1 - f) + T[..., i + 1] * f


def symmetric_grid(fn, mu, third):
    """fn(mu_i, mu_o, third) on mu × mu × third, computing only mu_i ≤ mu_o rows (symmetry)."""
    n = len(mu)
    out = np.zeros((n, n, len(third)))
    for i in range(n):
        v = fn(mu[i], mu[i:, None], third[None, :])
        out[i, i:] = v
        out[i:, i] = v
    return out


# ----------------------------------------------------------------------------- candidates


class Current:
    """Today's fast path: I on 80 × 80 × 32 (x, x, cos Δφ), trilinear."""

    def __init__(self, m, nu=80, nc=32, nodes=24):
        self.m, self.nu, self.nc = m, nu, nc
        mu = cos_of_axis(np.linspace(0, 1, nu))
        c = np.linspace(-1, 1, nc)
        self.T = symmetric_grid(lambda a, b, ph: sr.slope_integral(m, a, b, ph, nodes=nodes), mu, np.arccos(c))
        self.name = f"current {nu}x{nu}x{nc}"
        self.bytes = self.T.size * 4

    def __call__(self, mi, mo, cphi, phi):
        return trilinear(self.T, axis_of_cos(mi), axis_of_cos(mo), (cphi + 1) / 2)


class Residual(Current):
    """I − I_unc on a small (x, x, cos Δφ) table, trilinear, plus the closed-form unclamped part."""

    def __init__(self, m, nu, nc):
        super().__init__(m, nu, nc)
        self.e = sr.expectations(m)
        mu = cos_of_axis(np.linspace(0, 1, nu))
        c = np.linspace(-1, 1, nc)
        self.T = self.T - sr.unclamped(m, mu[:, None, None], mu[None, :, None], c[None, None, :], self.e)
        self.name = f"residual {nu}x{nu}x{nc}"

    def __call__(self, mi, mo, cphi, phi):
        return super().__call__(mi, mo, cphi, phi) + sr.unclamped(self.m, mi, mo, cphi, self.e)


class Split:
    """rest (three 1-D functions per direction, n1 nodes of x, linear) / (1 − r), r = K/I on an
    nv × nv × nph table over (v_i, v_o, Δφ), trilinear."""

    def __init__(self, m, n1=128, nv=16, nph=16, nodes=32, axis_m=None, oned_axis="x"):
        """`axis_m`: the roughness that scales the v axes (default m; the stack over m keeps
        each layer's own, so that its m-derivative is taken at fixed directions). `oned_axis`:
        the 1-D functions on x (as today's table) or on v."""
        self.m, self.axis_m, self.oned_axis = m, (m if axis_m is None else axis_m), oned_axis
        g = np.linspace(0, 1, n1)
        mu1 = np.maximum(cos_of_axis(g) if oned_axis == "x" else cos_of_v(g, self.axis_m), 1e-9)
        self.F = sr.normalized_direction_functions(m, mu1)
        mu = np.clip(cos_of_v(np.linspace(0, 1, nv), self.axis_m), 1e-12, 1.0)
        ph = np.linspace(0, np.pi, nph)

        def ratio(a, b, p):
            return sr.wedge_integral(m, a, b, p, nodes=nodes) / sr.slope_integral(m, a, b, p, nodes=nodes)

        self.R = symmetric_grid(ratio, mu, ph)
        self.name = f"split 1-D {n1} on {oned_axis} + K/I {nv}x{nv}x{nph}"
        self.bytes = self.F.size * 4 + self.R.size * 4

    def oned(self, mu):
        return axis_of_cos(mu) if self.oned_axis == "x" else v_of_cos(mu, self.axis_m)

    def parts(self, mi, mo, cphi, phi):
        rest = sr.rest_from_normalized(linear1d(self.F, self.oned(mi)), linear1d(self.F, self.oned(mo)), mi, mo, cphi)
        r = trilinear(self.R, v_of_cos(mi, self.axis_m), v_of_cos(mo, self.axis_m), phi / np.pi)
        return rest, r

    def __call__(self, mi, mo, cphi, phi):
        rest, r = self.parts(mi, mo, cphi, phi)
        return rest / (1 - r)


# ----------------------------------------------------------------------------- measurement

_REF = {}


def configurations(m, max_theta, samples):
    key = (m, max_theta, samples)
    if key not in _REF:
        ti, to, ph = sr.r3_configurations(max_theta, samples)
        mi, mo = np.cos(np.radians(ti)), np.cos(np.radians(to))
        phi = np.radians(ph)
        I, dI = sr.slope_integral(m, mi, mo, phi, derivative=True)
        _REF[key] = dict(mi=mi, mo=mo, cphi=np.cos(phi), phi=phi, I=I, dI=dI, deg=(ti, to, ph))
    return _REF[key]


def accuracy(rep, m, max_theta, samples):
    c = configurations(m, max_theta, samples)
    err = np.abs(rep(c["mi"], c["mo"], c["cphi"], c["phi"]) / c["I"] - 1)
    k = int(err.argmax())
    return dict(max=float(err.max()), mean=float(err.mean()), worst=[round(float(d[k]), 1) for d in c["deg"]])


def fmt(a):
    return (
        f"{100 * a['max']:.3f} % (mean {100 * a['mean']:.4f} %, worst {a['worst'][0]}/{a['worst'][1]}/{a['worst'][2]})"
    )


def check_f(samples):
    """The relative error of f equals that of I: today's table in numpy against `matte brdf`."""
    m = 0.30000001192092896  # the f32 roughness the Rust model stores
    out = {}
    for th in (80, 85):
        ti, to, ph = sr.r3_configurations(th, samples)
        f_ref, wi, wo = sr.eval_reference(m, ti, to, ph)
        pairs = "\n".join(
            " ".join(repr(float(v)) for v in np.concatenate([wi[:, k], wo[:, k]])) for k in range(len(ti))
        )
        matte = os.path.join(os.path.dirname(__file__), "../../.venv/bin/matte")
        if not os.path.exists(matte):
            matte = "/work/main/.venv/bin/matte"
        res = subprocess.run(
            [matte, "brdf", "--bsdf", "ginneken", "--param", "roughness=0.3", "--reflectance", "1", "--pairs", "-"],
            input=pairs,
            capture_output=True,
            text=True,
            check=True,
        )
        f = np.array(json.loads(res.stdout)["f"])
        rel_f = np.abs(f / f_ref - 1)
        cur = accuracy(Current(m), m, th, samples)
        out[th] = (float(rel_f.max()), cur["max"])
        print(
            f"θ ≤ {th}°: matte brdf (f, Rust f32) {100 * rel_f.max():.3f} %, numpy table (I) {100 * cur['max']:.3f} %",
            flush=True,
        )
    return out


# ----------------------------------------------------------------------------- textured roughness

M_MIN, M_MAX, M_NODES = 0.02, 4.0, 13


def u_nodes():
    u0, u1 = M_MIN / (1 + M_MIN), M_MAX / (1 + M_MAX)
    return np.linspace(u0, u1, M_NODES)


class SplitStack:
    """The split representation stacked over the roughness axis of `roughness_axis.rs` (13 nodes
    uniform in u = m/(1+m)), cubic Hermite in u with the m-derivatives as slopes (here by central
    differences, in Rust by the density-derivative trick of `integral_and_derivative`). Each
    layer keeps its own v axes (scaled by its node's m_j) and its derivative is taken at fixed
    directions, so the interpolant is smooth in m. Returns I and ∂I/∂m (the interpolant's exact
    derivative)."""

    def __init__(self, n1=128, nv=16, nph=16, oned_axis="x"):
        self.u = u_nodes()
        self.layers = []
        for u in self.u:
            m = u / (1 - u)
            h = 1e-3 * m
            a = Split(m, n1, nv, nph, oned_axis=oned_axis)
            p = Split(m + h, n1, nv, nph, axis_m=m, oned_axis=oned_axis)
            q = Split(m - h, n1, nv, nph, axis_m=m, oned_axis=oned_axis)
            dmdu = (1 + m) ** 2
            self.layers.append(
                dict(rep=a, F=a.F, R=a.R, dF=(p.F - q.F) / (2 * h) * dmdu, dR=(p.R - q.R) / (2 * h) * dmdu)
            )
        self.bytes = 2 * M_NODES * (a.F.size + a.R.size) * 4
        self.name = f"stack of {a.name}"

    def __call__(self, m, mi, mo, cphi, phi):
        u = m / (1 + m)
        du = self.u[1] - self.u[0]
        s = (u - self.u[0]) / du
        j = min(int(np.floor(s)), M_NODES - 2)
        s -= j
        h = [(1 + 2 * s) * (1 - s) ** 2, s * (1 - s) ** 2, s * s * (3 - 2 * s), s * s * (s - 1)]
        dh = [6 * s * s - 6 * s, 3 * s * s - 4 * s + 1, 6 * s - 6 * s * s, 3 * s * s - 2 * s]

        def combo(w):
            out = []
            for L, wv, wd in ((self.layers[j], w[0], w[1]), (self.layers[j + 1], w[2], w[3])):
                rep = L["rep"]
                Fi, Fo = rep.oned(mi), rep.oned(mo)
                vi, vo = v_of_cos(mi, rep.axis_m), v_of_cos(mo, rep.axis_m)
                t = phi / np.pi
                out.append(
                    (
                        wv * linear1d(L["F"], Fi) + wd * du * linear1d(L["dF"], Fi),
                        wv * linear1d(L["F"], Fo) + wd * du * linear1d(L["dF"], Fo),
                        wv * trilinear(L["R"], vi, vo, t) + wd * du * trilinear(L["dR"], vi, vo, t),
                    )
                )
            return [a + b for a, b in zip(*out)]

        Fi, Fo, r = combo(h)
        dFi, dFo, dr = combo(dh)
        dsdm = 1 / (du * (1 + m) ** 2)
        rest = sr.rest_from_normalized(Fi, Fo, mi, mo, cphi)
        drest = sr.rest_from_normalized(dFi, dFo, mi, mo, cphi) * dsdm  # rest is linear in F
        dr = dr * dsdm
        return rest / (1 - r), drest / (1 - r) + rest * dr / (1 - r) ** 2


# ----------------------------------------------------------------------------- main


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--samples", type=int, default=20000)
    ap.add_argument("--sweep", action="store_true", help="also sweep m ∈ [0.05, 4] (5000 samples each)")
    ap.add_argument("--textured", action="store_true", help="also the stack over m (Hermite), between nodes")
    ap.add_argument("--check-f", action="store_true", help="compare with the installed matte brdf (f)")
    ap.add_argument("--json", default=None, help="write all numbers here")
    ap.add_argument("--only-textured", action="store_true")
    args = ap.parse_args()
    results = {}
    if args.check_f:
        results["check_f"] = check_f(args.samples)
    for m in () if args.only_textured else (0.3, 0.5):
        reps = [
            lambda m=m: Current(m),
            lambda m=m: Residual(m, 24, 14),
            lambda m=m: Residual(m, 32, 16),
            lambda m=m: Split(m, 128, 12, 12),
            lambda m=m: Split(m, 128, 16, 16),
            lambda m=m: Split(m, 128, 20, 20),
            lambda m=m: Split(m, 128, 16, 16, oned_axis="v"),
        ]
        for make in reps:
            t = time.time()
            rep = make()
            built = time.time() - t
            a80, a85 = accuracy(rep, m, 80, args.samples), accuracy(rep, m, 85, args.samples)
            results[f"m={m} {rep.name}"] = dict(bytes=rep.bytes, build_s=built, theta80=a80, theta85=a85)
            print(
                f"m={m} {rep.name} ({rep.bytes / 1024:.1f} KB, {built:.1f} s): θ≤80° {fmt(a80)}; θ≤85° {fmt(a85)}",
                flush=True,
            )
    if args.sweep:
        for m in (0.05, 0.1, 0.2, 0.8, 1.3, 2.0, 3.0, 4.0):
            for make in (lambda m=m: Current(m), lambda m=m: Split(m, 128, 16, 16), lambda m=m: Split(m, 128, 20, 20)):
                rep = make()
                a80, a85 = accuracy(rep, m, 80, 5000), accuracy(rep, m, 85, 5000)
                results[f"sweep m={m} {rep.name}"] = dict(bytes=rep.bytes, theta80=a80, theta85=a85)
                print(f"sweep m={m} {rep.name}: θ≤80° {fmt(a80)}; θ≤85° {fmt(a85)}", flush=True)
    if args.textured:
        for oned_axis in ("x", "v"):
            t = time.time()
            stack = SplitStack(oned_axis=oned_axis)
            print(
                f"{stack.name}: {M_NODES} layers, {stack.bytes / 1024:.0f} KB, built {time.time() - t:.0f} s",
                flush=True,
            )
            for m in (0.05, 0.13, 0.45, 0.8, 1.3, 2.5):
                c = configurations(m, 80, 3000)
                I, dI = stack(m, c["mi"], c["mo"], c["cphi"], c["phi"])
                err = np.abs(I / c["I"] - 1)
                derr = np.abs(dI - c["dI"]) * m / c["I"]  # error of ∂ln I/∂ln m = that of ∂ln f/∂ln m
                results[f"textured ({oned_axis}) m={m}"] = dict(
                    max=float(err.max()), mean=float(err.mean()), dmax=float(derr.max()), dmean=float(derr.mean())
                )
                print(
                    f"textured ({oned_axis}) m={m} θ≤80°: f max {100 * err.max():.3f} % mean {100 * err.mean():.4f} %; "
                    f"∂ln f/∂ln m max {derr.max():.2e} mean {derr.mean():.2e}",
                    flush=True,
                )
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
