"""Fits matte's importance samplers: a clipped linearly transformed cosine (CLTC) with a
uniform share, `rust/brdf/cltc.rs`, per rough model. Writes `rust/brdf/sampler_fits.rs` and
prints the variance-ratio tables of `docs/sampling.md`.

    .venv/bin/python validation/fit_samplers.py [--matte target/release/matte]
        [--cache target/fit_samplers] [--out rust/brdf/sampler_fits.rs] [--quick]

What is minimised is the exact variance of the sampling weight `w = f cos θo / pdf` (ρ = 1)
by quadrature (a midpoint rule in (cos θo, φ), φ over [0, π] by the lobes' symmetry in the
plane of incidence), `Var = ∫ (f cos)² / p dω − E²`, as `matte bench --sampling` measures it
(`rust/bench/sampling.rs`). The CLTC density is `rust/brdf/cltc.rs`'s, in float64.

Models and their roughness variable `t ∈ [0, 1]` (one number that traces cheaply from what
the kernel already holds and maps the model's whole parameter range onto a bounded interval):
* Oren–Nayar, qualitative and full (ρ = 1, so the full model's ρ² interreflection term is at
  its largest): `t = σ² / (σ² + 0.09) = B / 0.45`, B the kernel's coefficient. σ ∈ [0, ∞) maps
  onto [0, 1): σ = 0.3 is t = 0.5, σ = 1 is t = 0.917. f is evaluated here in float64 (the
  formulas of `rust/brdf/oren_nayar.rs`, checked against the CLI).
* van Ginneken, both shadowing options: `t = u / 0.8`, `u = m / (1 + m)` the roughness axis
  of its per-lane tables (m ∈ (0, 4] onto (0, 1]; m = 0.3 is t = 0.288, m = 1 is t = 0.625).
  f comes from the matte CLI (`matte brdf --pairs`), once per (μ, m) on the quadrature grid,
  cached under `--cache`.

Three stages per model:
1. per (μ, t) on the fitting grid, the five CLTC parameters (a, b, c, d, p_uniform) that
   minimise the variance (Nelder–Mead on log a, b, log c, d, log p_u; continuation from the
   neighbouring grid point, so the optima form smooth surfaces);
2. a compact form, each parameter a low-degree polynomial in (μ, t) that is the cosine's
   value at t = 0 (a = c = 1, b = d = p_u = 0): `a = 1 + t P_a(μ, t)` etc., fitted to the
   optima by linear least squares;
3. the form's coefficients refined by minimising `Σ log(Var_form / Var_optimum)` over the
   grid (BFGS, gradients through the per-point parameter gradients), with the cosine's
   variance as a ceiling in the reported ratios (`Var_cosine / Var_form`).

Deterministic: fixed grids, fixed starting points, no random numbers.
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

PI = np.pi


# ---------------------------------------------------------------- quadrature ---------------

class Grid:
    """Midpoint rule in (z = cos θo, φ ∈ [0, π]); weights include the factor 2 of the mirror
    half."""

    def __init__(self, nz, nphi):
        z = (np.arange(nz) + 0.5) / nz
        phi = (np.arange(nphi) + 0.5) / nphi * PI
        self.z, self.phi = np.meshgrid(z, phi, indexing="ij")
        s = np.sqrt(1.0 - self.z ** 2)
        self.wo = np.stack([s * np.cos(self.phi), s * np.sin(self.phi), self.z], axis=-1).reshape(-1, 3)
        self.weight = 2.0 * (1.0 / nz) * (PI / nphi)
        self.n = nz * nphi


def wi_of(mu):
    mu = float(np.clip(mu, 0.0, 1.0))
    return np.array([np.sqrt(max(0.0, 1.0 - mu * mu)), 0.0, mu])


# ---------------------------------------------------------------- the sampler --------------

def cltc_pdf(params, wo):
    """The CLTC mixture's density at `wo` (n × 3) for wi in the +x half of the xz plane
    (`rust/brdf/cltc.rs`); `params` = (a, b, c, d, p_uniform), d clamped to ≤ 0."""
    a, b, c, d, pu = params
    d = min(d, 0.0)
    wx, wy, wz = wo[:, 0], wo[:, 1], wo[:, 2]
    a_bd = a - b * d
    qx = c * (wx - b * wz)
    qy = a_bd * wy
    qz = c * (a * wz - d * wx)
    det = c * a_bd
    q2 = np.maximum(qx * qx + qy * qy + qz * qz, 1e-300)
    jac = det / q2
    s = 0.5 * (1.0 + 1.0 / np.sqrt(1.0 + d * d))
    lobe = jac * jac * np.maximum(qz, 0.0) / (PI * s)
    return pu / (2.0 * PI) + (1.0 - pu) * lobe


def variance(fc, params, grid):
    """`Var = ∫ (f cos)² / p dω − E²` for the weight under the CLTC `params`; `fc` = f cos θo
    on the grid."""
    p = cltc_pdf(params, grid.wo)
    with np.errstate(divide="ignore", invalid="ignore"):
        m2 = np.where(fc > 0.0, fc * fc / p, 0.0)
    e = fc.sum() * grid.weight
    return m2.sum() * grid.weight - e * e


def cosine_variance(fc, grid):
    e = fc.sum() * grid.weight
    return (PI * fc * fc / grid.wo[:, 2]).sum() * grid.weight - e * e


# ---------------------------------------------------------------- the models ---------------

def on_coefficients(t):
    """Oren–Nayar's kernel coefficients (A, B, C3 prefactor, interreflection prefactor) at
    `t = σ²/(σ² + 0.09)`."""
    t = min(t, 1.0 - 1e-12)
    s2 = 0.09 * t / (1.0 - t)
    return (1.0 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09), 0.125 * s2 / (s2 + 0.09), 0.17 * s2 / (s2 + 0.13))


def sigma_of_t(t):
    return np.sqrt(0.09 * t / (1.0 - t)) if t < 1.0 else np.inf


def t_of_sigma(sigma):
    return sigma * sigma / (sigma * sigma + 0.09)


def on_qualitative_f(t, wi, wo):
    """f (1/sr) of Oren–Nayar's qualitative model, ρ = 1 (`rust/brdf/oren_nayar.rs`)."""
    a, b, _, _ = on_coefficients(t)
    s = wi[0] * wo[:, 0] + wi[1] * wo[:, 1]
    g = a + np.maximum(s, 0.0) * b / np.maximum(np.maximum(wi[2], wo[:, 2]), 1e-7)
    return g / PI


def on_full_f(t, wi, wo):
    """f of Oren–Nayar's full model (C1–C3 and the ρ² interreflection term), ρ = 1."""
    a, b, c3, l2 = on_coefficients(t)
    tiny = 1e-7
    sin_i = np.hypot(wi[0], wi[1])
    sin_o = np.hypot(wo[:, 0], wo[:, 1])
    sp = sin_i * sin_o
    s = wi[0] * wo[:, 0] + wi[1] * wo[:, 1]
    cos_phi = np.where(sp > tiny, np.clip(s / np.maximum(sp, tiny), -1.0, 1.0), 0.0)
    i_alpha = wi[2] < wo[:, 2]
    cos_a = np.where(i_alpha, wi[2], wo[:, 2])
    sin_a = np.where(i_alpha, sin_i, sin_o)
    cos_b = np.where(i_alpha, wo[:, 2], wi[2])
    sin_b = np.where(i_alpha, sin_o, sin_i)
    alpha, beta = np.arccos(np.clip(cos_a, -1, 1)), np.arccos(np.clip(cos_b, -1, 1))
    tan_b = sin_b / np.maximum(cos_b, tiny)
    tan_half = (sin_a + sin_b) / np.maximum(cos_a + cos_b, tiny)
    tbp = beta * 2.0 / PI
    c2 = np.where(cos_phi >= 0.0, b * sin_a, b * (sin_a - tbp ** 3))
    c3v = c3 * (4.0 * alpha * beta / PI ** 2) ** 2
    direct = a + cos_phi * c2 * tan_b + (1.0 - np.abs(cos_phi)) * c3v * tan_half
    inter = l2 * (1.0 - cos_phi * tbp * tbp)
    return np.maximum(direct + inter, 0.0) / PI


def m_of_t(t):
    """van Ginneken's roughness m at `t = (m/(1+m))/0.8`."""
    u = 0.8 * t
    return min(u / (1.0 - u), 4.0)


def t_of_m(m):
    return m / (1.0 + m) / 0.8


class Cli:
    """f from `matte brdf --pairs`, cached per (model, parameters, μ, grid)."""

    def __init__(self, exe, cache):
        self.exe, self.cache = exe, cache
        os.makedirs(cache, exist_ok=True)

    def f(self, bsdf, params, mus, grid, tag):
        """f (1/sr, ρ = 1) on `grid` at each μ of `mus`: array (len(mus), grid.n), float64."""
        key = "_".join([bsdf] + [f"{k}={v}" for k, v in params] + [tag])
        path = os.path.join(self.cache, key + ".npz")
        mus = np.asarray(mus, dtype=np.float64)
        if os.path.exists(path):
            d = np.load(path)
            if d["mus"].shape == mus.shape and np.array_equal(d["mus"], mus):
                return d["f"]
        lines = []
        for mu in mus:
            wi = wi_of(mu)
            pairs = np.concatenate([np.broadcast_to(wi, grid.wo.shape), grid.wo], axis=1)
            lines.append(pairs)
        text = "\n".join(" ".join(f"{x:.9g}" for x in row) for row in np.concatenate(lines))
        cmd = [self.exe, "brdf", "--bsdf", bsdf, "--reflectance", "1", "--pairs", "-"]
        for k, v in params:
            cmd += ["--param", f"{k}={v}"]
        out = subprocess.run(cmd, input=text + "\n", capture_output=True, text=True, check=True).stdout
        f = np.asarray(json.loads(out)["f"], dtype=np.float64).reshape(len(mus), grid.n)
        np.savez(path, mus=mus, f=f)
        return f


# ---------------------------------------------------------------- optimisers ---------------

def params_of_x(x):
    """CLTC parameters from the optimiser's variables (log a, b, log c, d, log p_u)."""
    return (np.exp(x[0]), x[1], np.exp(x[2]), min(x[3], 0.0), min(np.exp(x[4]), 0.95))


def x_of_params(p):
    a, b, c, d, pu = p
    return np.array([np.log(a), b, np.log(c), d, np.log(np.clip(pu, 1e-9, 0.95))])


def nelder_mead(fun, x0, step, iters=2000, tol=1e-9):
    """Plain Nelder–Mead (standard coefficients), deterministic; stops when the simplex's
    values agree to `tol` relative."""
    n = len(x0)
    simplex = [np.array(x0, dtype=float)]
    for k in range(n):
        v = np.array(x0, dtype=float)
        v[k] += step[k]
        simplex.append(v)
    values = [fun(v) for v in simplex]
    for _ in range(iters):
        order = np.argsort(values)
        simplex = [simplex[i] for i in order]
        values = [values[i] for i in order]
        if abs(values[-1] - values[0]) <= tol * abs(values[0]):
            break
        centre = np.mean(simplex[:-1], axis=0)
        xr = centre + (centre - simplex[-1])
        fr = fun(xr)
        if fr < values[0]:
            xe = centre + 2.0 * (centre - simplex[-1])
            fe = fun(xe)
            simplex[-1], values[-1] = (xe, fe) if fe < fr else (xr, fr)
        elif fr < values[-2]:
            simplex[-1], values[-1] = xr, fr
        else:
            inside = fr >= values[-1]
            xc = centre + (0.5 * (simplex[-1] - centre) if inside else 0.5 * (xr - centre))
            fc = fun(xc)
            if fc < min(fr, values[-1]):
                simplex[-1], values[-1] = xc, fc
            else:
                for k in range(1, n + 1):
                    simplex[k] = simplex[0] + 0.5 * (simplex[k] - simplex[0])
                    values[k] = fun(simplex[k])
    k = int(np.argmin(values))
    return simplex[k], values[k]


def optimum(fc, grid, inits):
    """The CLTC minimising the weight variance for `fc` (f cos θo on `grid`): Nelder–Mead from
    each of `inits` (the neighbouring optima) and from three variants of the first (the clipped and unclipped
    lobes are separate basins: with p_u → 0 any d < 0 costs an infinite variance), each
    restarted once from its best point; the best of all."""
    def fun(x):
        v = variance(fc, params_of_x(x), grid)
        return v if np.isfinite(v) else 1e300
    starts = [np.array(x, dtype=float) for x in inits]
    for d, pu in ((-0.2, 0.1), (-0.03, 0.01), (0.0, 1e-6)):
        x = np.array(inits[0], dtype=float)
        x[3], x[4] = d, np.log(pu)
        starts.append(x)
    best = (None, np.inf)
    for x in starts:
        x, v = nelder_mead(fun, x, [0.1, 0.1, 0.1, 0.1, 1.0])
        x, v = nelder_mead(fun, x, [0.03, 0.03, 0.03, 0.03, 0.5])
        if v < best[1]:
            best = (x, v)
    return best


# ---------------------------------------------------------------- stage 1 ------------------

FIT_THETA = [0.0, 15.0, 30.0, 40.0, 50.0, 60.0, 67.0, 73.0, 78.0, 82.0, 85.0, 87.0, 89.0]
FIT_T = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]


def stage1(fcs, grid, log=None):
    """Per-point optima. `fcs[k][j]`: f cos θo at FIT_T[k], FIT_THETA[j]. Returns the
    unconstrained optima X (nt, nθ, 5), their variances and the cosine's."""
    nt, nth = len(fcs), len(fcs[0])
    X = np.zeros((nt, nth, 5))
    V = np.zeros((nt, nth))
    Vc = np.zeros((nt, nth))
    for k in range(nt):
        x = x_of_params((1.0, 0.0, 1.0, 0.0, 1e-6))
        for j in range(nth):
            fc = fcs[k][j]
            Vc[k, j] = cosine_variance(fc, grid)
            x, v = optimum(fc, grid, [x] if k == 0 else [x, X[k - 1, j]])
            X[k, j], V[k, j] = x, v
            if log:
                log(f"  t={FIT_T[k]:.2f} θi={FIT_THETA[j]:4.1f}: Var cosine {Vc[k, j]:.4g}, optimum {v:.4g} "
                    f"({Vc[k, j] / max(v, 1e-12):.2f}×) {np.round(params_of_x(x), 4)}")
    return X, V, Vc


# ---------------------------------------------------------------- the compact form ---------

# The cosine's parameters (a, b, c, d, p_uniform): every form takes them at t = 0.
BASE = np.array([1.0, 0.0, 1.0, 0.0, 0.0])
NAMES = ["a", "b", "c", "d", "p_uniform"]


class Form:
    """`param_k(μ, t) = BASE_k + t · g_k(μ) · Σ_ij C[k, i, j] μ^i t^j`, with `g_k = sin θi` (the
    parameter takes the cosine's value at normal incidence, where the model's lobe is
    rotationally symmetric and, for Oren–Nayar, constant) or 1 (`free_at_normal`: a and c may
    differ from 1 there). Then a, c ≥ 0.05, d ≤ 0 and p_uniform ∈ [0, 0.9]
    (`rust/brdf/cltc.rs` clamps d; `CltcFit::sampler` the others)."""

    def __init__(self, deg_mu, deg_t, free_at_normal=()):
        self.deg_mu, self.deg_t = deg_mu, deg_t
        self.free_at_normal = tuple(free_at_normal)
        self.shape = (5, deg_mu + 1, deg_t + 1)

    def size(self):
        return int(np.prod(self.shape))

    def basis(self, mu, t):
        """(5, deg_mu+1, deg_t+1): ∂ param_k / ∂ C[k, i, j] at (μ, t)."""
        s = np.sqrt(max(0.0, 1.0 - mu * mu))
        mono = np.outer(mu ** np.arange(self.deg_mu + 1), t ** np.arange(self.deg_t + 1))
        g = np.array([1.0 if k in self.free_at_normal else s for k in range(5)])
        return t * g[:, None, None] * mono[None]

    def raw(self, C, mu, t):
        return BASE + (C.reshape(self.shape) * self.basis(mu, t)).sum(axis=(1, 2))


def clamp_params(p):
    a, b, c, d, pu = p
    return (max(a, 0.05), b, max(c, 0.05), min(d, 0.0), min(max(pu, 0.0), 0.9))


def stage2(form, X, mus, ts):
    """Least-squares coefficients of `form` to the per-point optima (points at normal
    incidence, where the basis of the sin θi-scaled parameters vanishes, are skipped for
    those)."""
    C = np.zeros(form.shape)
    for k in range(5):
        rows, rhs = [], []
        for a_t, t in enumerate(ts):
            for j, mu in enumerate(mus):
                bk = form.basis(mu, t)[k]
                if not np.any(bk):
                    continue
                rows.append(bk.ravel())
                rhs.append(params_of_x(X[a_t, j])[k] - BASE[k])
        C[k] = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)[0].reshape(form.shape[1:])
    return C.ravel()


def point_gradient(fc, grid, p, h=1e-5):
    """`(log Var, ∂ log Var / ∂ p)` at the raw parameters p (central differences through
    the clamps)."""
    v0 = variance(fc, clamp_params(p), grid)
    g = np.zeros(5)
    for k in range(5):
        dp = np.zeros(5)
        dp[k] = h
        vp = variance(fc, clamp_params(p + dp), grid)
        vm = variance(fc, clamp_params(p - dp), grid)
        g[k] = (np.log(vp) - np.log(vm)) / (2 * h)
    return np.log(v0), g


class Objective:
    """`J(C) = mean over the grid of log Var(form(C))`: the mean log-variance ratio against any
    fixed reference. Points with a (numerically) zero optimum variance are left out."""

    def __init__(self, form, fcs, grid, mus, ts, V):
        self.form, self.grid = form, grid
        self.points = [(fcs[a][j], mu, t) for a, t in enumerate(ts) for j, mu in enumerate(mus)
                       if V[a, j] > 1e-10]

    def value(self, C):
        total = 0.0
        for fc, mu, t in self.points:
            v = variance(fc, clamp_params(self.form.raw(C, mu, t)), self.grid)
            if not (v > 0 and np.isfinite(v)):
                return np.inf
            total += np.log(v)
        return total / len(self.points)

    def value_and_gradient(self, C):
        total, grad = 0.0, np.zeros(self.form.size())
        for fc, mu, t in self.points:
            p = self.form.raw(C, mu, t)
            lv, g = point_gradient(fc, self.grid, p)
            if not np.isfinite(lv) or not np.all(np.isfinite(g)):
                return np.inf, grad
            total += lv
            grad += (g[:, None, None] * self.form.basis(mu, t)).ravel()
        n = len(self.points)
        return total / n, grad / n


def bfgs(obj, x0, iters=200, log=None, gtol=1e-6):
    """BFGS with a backtracking (Armijo) line search on `obj.value_and_gradient`."""
    x = np.array(x0, dtype=float)
    f, g = obj.value_and_gradient(x)
    H = np.eye(len(x)) * 1e-2
    for it in range(iters):
        step = -H @ g
        slope = g @ step
        if slope >= 0:
            H = np.eye(len(x)) * 1e-2
            step, slope = -H @ g, -(g @ H @ g)
        alpha, fn = 1.0, None
        for _ in range(30):
            fn = obj.value(x + alpha * step)
            if fn <= f + 1e-4 * alpha * slope:
                break
            alpha *= 0.5
        else:
            break
        xn = x + alpha * step
        fn, gn = obj.value_and_gradient(xn)
        s, y = xn - x, gn - g
        sy = s @ y
        if sy > 1e-12:
            rho = 1.0 / sy
            I = np.eye(len(x))
            H = (I - rho * np.outer(s, y)) @ H @ (I - rho * np.outer(y, s)) + rho * np.outer(s, s)
        improvement = f - fn
        x, f, g = xn, fn, gn
        if log and it % 10 == 0:
            log(f"    BFGS {it}: J = {f:.6f}, |g| = {np.linalg.norm(g):.2e}")
        if np.linalg.norm(g) < gtol or improvement < 1e-9:
            break
    return x, f
