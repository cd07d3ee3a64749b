"""Fits matte's importance samplers: a clipped linearly transformed cosine (CLTC) with a
uniform share, `rust/brdf/src/cltc.rs`, per rough model. Writes `rust/brdf/src/sampler_fits.rs` and
prints the variance-ratio tables of `docs/sampling.md`.

    .venv/bin/python validation/generators/fit_samplers.py [--matte target/release/matte]
        [--cache target/fit_samplers] [--out rust/brdf/src/sampler_fits.rs] [--quick]

What is minimised is the exact variance of the sampling weight `w = f cos θo / pdf` (ρ = 1)
by quadrature (a midpoint rule in (cos θo, φ), φ over [0, π] by the lobes' symmetry in the
plane of incidence), `Var = ∫ (f cos)² / p dω − E²`, as `matte bench --sampling` measures it
(`rust/matte/src/bench/sampling.rs`). The CLTC density is `rust/brdf/src/cltc.rs`'s, in float64.

Models and their roughness variable `t ∈ [0, 1]` (one number that traces cheaply from what
the kernel already holds and maps the model's whole parameter range onto a bounded interval):
* Oren–Nayar, qualitative and full (ρ = 1, so the full model's ρ² interreflection term is at
  its largest): `t = σ² / (σ² + 0.09) = B / 0.45`, B the kernel's coefficient. σ ∈ [0, ∞) maps
  onto [0, 1): σ = 0.3 is t = 0.5, σ = 1 is t = 0.917. f is evaluated here in float64 (the
  formulas of `rust/brdf/src/models/oren_nayar.rs`, checked against the CLI).
* Burley: `t = r`, its roughness.
* van Ginneken: `t = u / 0.8`, `u = m / (1 + m)` the roughness axis
  of its per-lane tables (m ∈ (0, 4] onto (0, 1]; m = 0.3 is t = 0.288, m = 1 is t = 0.625).
  f comes from the matte CLI (`matte brdf --pairs`), once per (μ, m) on the quadrature grid,
  cached under `--cache`. Fitted for both shadowing options; their fits differ by 2–3 % in
  variance, so one fit (vginneken's) serves both and `height_correlated` is reported with it.

Three stages per model:
1. per (μ, t) on the fitting grid, the five CLTC parameters (a, b, c, d, p_uniform) that
   minimise the variance (Nelder–Mead on log a, b, log c, d, log p_u; continuation from the
   neighbouring grid point, so the optima form smooth surfaces);
2. a compact form, each parameter a low-degree polynomial in (μ, t) that is the cosine's
   value at t = 0 (a = c = 1, b = d = p_u = 0): `a = 1 + t P_a(μ, t)` etc., fitted to the
   optima by linear least squares;
3. the form's coefficients refined by minimising the mean of `log Var_form` over the grid
   (the mean log-ratio to the optima), with a penalty wherever `Var_form` exceeds the
   cosine's (BFGS, gradients through the per-point parameter gradients);
then a check of the form on a dense (t, θi) grid (finite everywhere, the smallest ratio to the
cosine), the tables of `docs/sampling.md` (variance ratios cosine/fitted at roughness 0.3 and 1
against EON's fit at the best roughness for the model), whether van Ginneken's two shadowing
options need fits of their own, and a screening of Wolff and Burley (the per-point optimum's
gain, an upper bound on any fit's).

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
        s = np.sqrt(1.0 - self.z**2)
        self.wo = np.stack([s * np.cos(self.phi), s * np.sin(self.phi), self.z], axis=-1).reshape(-1, 3)
        self.weight = 2.0 * (1.0 / nz) * (PI / nphi)
        self.n = nz * nphi


def wi_of(mu):
    mu = float(np.clip(mu, 0.0, 1.0))
    return np.array([np.sqrt(max(0.0, 1.0 - mu * mu)), 0.0, mu])


# ---------------------------------------------------------------- the sampler --------------


def cltc_pdf(params, wo):
    """The CLTC mixture's density at `wo` (n × 3) for wi in the +x half of the xz plane
    (`rust/brdf/src/cltc.rs`); `params` = (a, b, c, d, p_uniform), d clamped to ≤ 0."""
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
    """f (1/sr) of Oren–Nayar's qualitative model, ρ = 1 (`rust/brdf/src/models/oren_nayar.rs`)."""
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
    c2 = np.where(cos_phi >= 0.0, b * sin_a, b * (sin_a - tbp**3))
    c3v = c3 * (4.0 * alpha * beta / PI**2) ** 2
    direct = a + cos_phi * c2 * tan_b + (1.0 - np.abs(cos_phi)) * c3v * tan_half
    inter = l2 * (1.0 - cos_phi * tbp * tbp)
    return np.maximum(direct + inter, 0.0) / PI


def burley_f(t, wi, wo):
    """f of Burley's diffuse, ρ = 1, at roughness r = t (`rust/brdf/src/models/burley.rs`)."""
    schlick = lambda mu: (1.0 - np.clip(mu, 0.0, 1.0)) ** 5  # noqa: E731
    f_i, f_o = schlick(wi[2]), schlick(wo[:, 2])
    f_d = (1.0 - 0.5 * f_i) * (1.0 - 0.5 * f_o)
    r_r = t * (1.0 + wo @ wi)
    return (f_d + r_r * (f_i + f_o + f_i * f_o * (r_r - 1.0))) / PI


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
FIT_T = [0.025, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]


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
                log(
                    f"  t={FIT_T[k]:.2f} θi={FIT_THETA[j]:4.1f}: Var cosine {Vc[k, j]:.4g}, optimum {v:.4g} "
                    f"({Vc[k, j] / max(v, 1e-12):.2f}×) {np.round(params_of_x(x), 4)}"
                )
    return X, V, Vc


# ---------------------------------------------------------------- the compact form ---------

# The cosine's parameters (a, b, c, d, p_uniform): every form takes them at t = 0.
BASE = np.array([1.0, 0.0, 1.0, 0.0, 0.0])
NAMES = ["a", "b", "c", "d", "p_uniform"]


class Form:
    """`param_k(μ, t) = BASE_k + t · g_k(μ) · Σ_ij C[k, i, j] μ^i t^j`, with `g_k = sin θi` (the
    parameter takes the cosine's value at normal incidence, where the model's lobe is
    rotationally symmetric and, for Oren–Nayar, constant) or 1 (`free_at_normal`: a and c may
    differ from 1 there). Then a, c ≥ 0.05, d ≤ 0 and p_uniform ∈ [−0.1 d, 0.9]
    ([`clamp_params`]; `CltcFit::sampler` in `rust/brdf/src/cltc.rs`)."""

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


# The uniform share is at least this times −d: wherever the lobe is clipped (d < 0) the
# mixture has density on the whole hemisphere, so that no fit, between its grid points or
# beyond, leaves a direction with f > 0 unsampled (a bias, and an infinite variance).
UNIFORM_PER_CLIP = 0.1


def clamp_params(p):
    """`CltcFit::sampler`'s clamps on the raw form."""
    a, b, c, d, pu = p
    d = min(d, 0.0)
    return (max(a, 0.05), b, max(c, 0.05), d, min(max(pu, -UNIFORM_PER_CLIP * d), 0.9))


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
        lp = np.log(variance(fc, clamp_params(p + dp), grid))
        lm = np.log(variance(fc, clamp_params(p - dp), grid))
        g[k] = (lp - lm) / (2 * h)
    return np.log(v0), g


# Weight of the penalty on a variance above the cosine's (see `Objective`).
PENALTY = 10.0


class Objective:
    """`J(C) = mean over the grid of [log Var(form(C)) + PENALTY · max(0, log(Var / Var_cosine))²]`:
    the mean log-variance ratio against any fixed reference, with a penalty wherever the fit
    would sample worse than the cosine (near normal incidence at small roughness, where every
    sampler's variance is tiny, the polynomials would otherwise trade it away for gains
    elsewhere). Points with a (numerically) zero optimum variance are left out."""

    def __init__(self, form, fcs, grid, mus, ts, V):
        self.form, self.grid = form, grid
        self.points = [
            (fcs[a][j], mu, t, np.log(cosine_variance(fcs[a][j], grid)))
            for a, t in enumerate(ts)
            for j, mu in enumerate(mus)
            if V[a, j] > 1e-10
        ]

    def value(self, C, penalty=PENALTY):
        total = 0.0
        for fc, mu, t, lc in self.points:
            v = variance(fc, clamp_params(self.form.raw(C, mu, t)), self.grid)
            if not (v > 0 and np.isfinite(v)):
                return np.inf
            total += np.log(v) + penalty * max(0.0, np.log(v) - lc) ** 2
        return total / len(self.points)

    def value_and_gradient(self, C):
        total, grad = 0.0, np.zeros(self.form.size())
        for fc, mu, t, lc in self.points:
            p = self.form.raw(C, mu, t)
            lv, g = point_gradient(fc, self.grid, p)
            if not np.isfinite(lv) or not np.all(np.isfinite(g)):
                return np.inf, grad
            excess = max(0.0, lv - lc)
            total += lv + PENALTY * excess**2
            grad += ((1.0 + 2.0 * PENALTY * excess) * g[:, None, None] * self.form.basis(mu, t)).ravel()
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


# ---------------------------------------------------------------- EON's fit as a baseline --


def eon_params(r, mu):
    """EON's CLTC (`rust/brdf/src/models/eon.rs`, `EonKernel::sampler`) at roughness r."""
    poly2 = lambda c0, c1, c2: c0 + c1 * mu + c2 * mu * mu  # noqa: E731
    a = 1 + r * (poly2(0.303392, -0.518982, 0.111709) + r * (-0.276266 + 0.335918 * mu))
    b = r * ((-1.16407 + 1.15859 * mu) + r * (0.150815 - 0.150105 * mu)) / (mu**3 - 1.43545)
    c = 1 + r * poly2(0.20013, -0.506373, 0.261777)
    d = r * poly2(0.540852, -1.01625, 0.475392) / poly2(-1.0743, 0.0725628, 1.0)
    pu = r**0.125 * (0.162925 - 0.372058 * mu + 0.538233 * mu**2 - 0.290822 * mu**3)
    return (a, b, c, min(d, 0.0), pu)


def best_eon_roughness(fcs, mus, grid):
    """The EON roughness r ∈ [0, 1] whose sampler minimises the mean log variance over the
    incidences of `fcs` (golden-section search): EON's fit reused with the best mapping any
    roughness conversion could give, per roughness."""

    def cost(r):
        vs = [variance(fc, eon_params(r, mu), grid) for fc, mu in zip(fcs, mus) if mu < 1.0]
        return np.mean(np.log(np.maximum(vs, 1e-300)))

    lo, hi = 0.0, 1.0
    k = (np.sqrt(5.0) - 1.0) / 2.0
    x1, x2 = hi - k * (hi - lo), lo + k * (hi - lo)
    f1, f2 = cost(x1), cost(x2)
    for _ in range(30):
        if f1 < f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - k * (hi - lo)
            f1 = cost(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + k * (hi - lo)
            f2 = cost(x2)
    # The ends too: at r → 0 the uniform share still goes as r^(1/8), so the search cannot
    # reach r = 0 (the cosine) from inside.
    return min((0.5 * (lo + hi), 0.0, 1.0), key=cost)


# ---------------------------------------------------------------- the models fitted --------

REPORT_THETA = [0.0, 15.0, 30.0, 45.0, 60.0, 70.0, 75.0, 80.0, 85.0, 89.0]


class Model:
    """One model to fit: `name` (the Rust constant), how f is had at (t, μ's) on a grid, its
    roughness parameter and the map to t."""

    def __init__(self, name, label, f_at, param, t_of, form, t_text, samples_with=None):
        self.name, self.label, self.f_at, self.param, self.t_of, self.form = name, label, f_at, param, t_of, form
        self.t_text = t_text
        # Fitted for comparison only: the model samples with this other model's fit.
        self.samples_with = samples_with

    def fcs(self, ts, mus, grid, tag):
        return [[f * grid.wo[:, 2] for f in self.f_at(t, mus, grid, tag)] for t in ts]


def analytic(f):
    return lambda t, mus, grid, tag: np.array([f(t, wi_of(mu), grid.wo) for mu in mus])


def from_cli(cli, bsdf, extra):
    def f_at(t, mus, grid, tag):
        params = [("roughness", f"{m_of_t(t):.9g}")] + extra
        return cli.f(bsdf, params, mus, grid, tag)

    return f_at


def models(cli):
    on_form = Form(DEG_MU, DEG_T)
    # van Ginneken's lobe is not the cosine at normal incidence (f varies with θo there):
    # a = c may differ from 1 at μ = 1.
    vg_form = Form(DEG_MU, DEG_T, free_at_normal=(0, 2))
    return [
        Model(
            "OREN_NAYAR_QUALITATIVE",
            "Oren–Nayar qualitative",
            analytic(on_qualitative_f),
            "sigma",
            t_of_sigma,
            on_form,
            "σ²/(σ² + 0.09)",
        ),
        Model(
            "OREN_NAYAR_FULL",
            "Oren–Nayar full (ρ = 1)",
            analytic(on_full_f),
            "sigma",
            t_of_sigma,
            on_form,
            "σ²/(σ² + 0.09)",
        ),
        Model(
            "GINNEKEN",
            "van Ginneken, shadowing = vginneken",
            from_cli(cli, "ginneken", [("shadowing", "vginneken")]),
            "roughness",
            t_of_m,
            vg_form,
            "1.25 m/(1 + m); fitted with shadowing = vginneken, used for both options",
        ),
        # Fitted to compare: the two shadowing options' optimal fits differ by 2–3 % in
        # variance, so `height_correlated` samples with the `vginneken` fit.
        Model(
            "GINNEKEN_HEIGHT_CORRELATED",
            "van Ginneken, shadowing = height_correlated",
            from_cli(cli, "ginneken", [("shadowing", "height_correlated")]),
            "roughness",
            t_of_m,
            vg_form,
            "1.25 m/(1 + m)",
            samples_with="GINNEKEN",
        ),
        # Burley's lobe at normal incidence is not the cosine either (the retro-reflection).
        Model("BURLEY", "Burley", analytic(burley_f), "roughness", lambda r: r, vg_form, "r"),
    ]


DEG_MU, DEG_T = 3, 2
FIT_GRID = (96, 96)
REPORT_GRID = (256, 256)


def round_coefficients(C):
    """The coefficients as written into the Rust file (10 significant digits)."""
    return np.array([float(f"{c:.10g}") for c in C])


def fit(model, cli, cache, log):
    grid = Grid(*FIT_GRID)
    mus = [np.cos(np.radians(th)) for th in FIT_THETA]
    fcs = model.fcs(FIT_T, mus, grid, f"fit{FIT_GRID[0]}")
    path = os.path.join(cache, f"fit_{model.name}_{DEG_MU}{DEG_T}_{FIT_GRID[0]}.npz")
    s1 = os.path.join(cache, f"stage1_{model.name}_{FIT_GRID[0]}.npz")
    if os.path.exists(s1):
        d = np.load(s1)
        X, V, Vc = d["X"], d["V"], d["Vc"]
    else:
        log(f"{model.label}: per-point optima")
        X, V, Vc = stage1(fcs, grid, log=log)
        np.savez(s1, X=X, V=V, Vc=Vc)
    obj = Objective(model.form, fcs, grid, mus, FIT_T, V)
    model.objective = obj
    if os.path.exists(path):
        d = np.load(path)
        return d["C"], d["V"], d["Vc"], float(d["J"]), float(d["J_opt"])
    C = stage2(model.form, X, mus, FIT_T)
    log(f"{model.label}: refining the {model.form.size()} coefficients")
    C, J = bfgs(obj, C, iters=400, log=log)
    C = round_coefficients(C)
    J = obj.value(C, penalty=0.0)
    J_opt = np.mean([np.log(V[a, j]) for a in range(len(FIT_T)) for j in range(len(mus)) if V[a, j] > 1e-10])
    np.savez(path, C=C, V=V, Vc=Vc, J=J, J_opt=J_opt)
    return C, V, Vc, J, J_opt


# ---------------------------------------------------------------- checks and report --------


def dense_check(model, C, log):
    """The form over a dense (t, θi) grid on a coarse quadrature: the weight's variance must
    be finite everywhere (a clipped lobe needs a uniform share), and the worst ratio
    cosine/fitted is printed (where the fit gains least or loses), among the points where the
    cosine's variance exceeds 10⁻⁵ E²."""
    grid = Grid(48, 48)
    ts = np.linspace(0.05, 1.0, 20)
    thetas = np.linspace(0.0, 89.5, 37)
    mus = [np.cos(np.radians(th)) for th in thetas]
    worst = (np.inf, None)
    worst_far = (np.inf, None)
    for t in ts:
        for th, mu, fc in zip(thetas, mus, model.fcs([t], mus, grid, "dense48")[0]):
            vc = cosine_variance(fc, grid)
            v = variance(fc, clamp_params(model.form.raw(C, mu, t)), grid)
            if not np.isfinite(v):
                raise SystemExit(f"{model.name}: infinite variance at t={t:.3f} θi={th:.1f}")
            # Below 10⁻⁵ E² (the weight's relative spread under 0.3 %) neither variance
            # matters, and this coarse quadrature does not resolve their ratio.
            e2 = (fc.sum() * grid.weight) ** 2
            if vc <= 1e-5 * e2:
                continue
            ratio = vc / max(v, 1e-300)
            if ratio < worst[0]:
                worst = (ratio, (t, th))
            if th >= 45.0 and ratio < worst_far[0]:
                worst_far = (ratio, (t, th))
    log(
        f"  dense check: smallest ratio cosine/fitted {worst[0]:.2f} at t, θi = {worst[1]}; "
        f"for θi ≥ 45°: {worst_far[0]:.2f} at {worst_far[1]}"
    )
    return worst, worst_far


def report(model, C, log):
    """Rows per roughness 0.3 and 1 (in the model's own parameter) and REPORT_THETA: the
    weight's variance under the cosine, the fitted sampler and EON's fit at the best
    roughness, on the REPORT_GRID quadrature."""
    grid = Grid(*REPORT_GRID)
    mus = [np.cos(np.radians(th)) for th in REPORT_THETA]
    out = []
    for rough in (0.3, 1.0):
        t = model.t_of(rough)
        fcs = model.fcs([t], mus, grid, f"report{REPORT_GRID[0]}")[0]
        r_eon = best_eon_roughness(fcs, mus, grid)
        rows = []
        for th, mu, fc in zip(REPORT_THETA, mus, fcs):
            e = fc.sum() * grid.weight
            vc = cosine_variance(fc, grid)
            v = variance(fc, clamp_params(model.form.raw(C, mu, t)), grid)
            ve = variance(fc, eon_params(r_eon, mu), grid)
            rows.append(dict(theta_i=th, albedo=e, var_cosine=vc, var_fit=v, var_eon=ve))
        out.append(dict(roughness=rough, t=t, eon_r=r_eon, rows=rows))
    return out


def ratio_text(vc, v, e):
    floor = 1e-6 * e * e
    return "—" if vc <= floor or v <= floor else f"{vc / v:.2f}"


def markdown(model, rep):
    """The docs' table: per incidence, the variance ratios cosine/fitted and cosine/EON's fit
    at both roughnesses."""
    p = model.param
    head = "| θi |" + "".join(
        f" Var cosine, {p} = {r['roughness']:g} | ratio fitted | ratio EON fit (r = {r['eon_r']:.2f}) |" for r in rep
    )
    lines = [head, "|---" * (1 + 3 * len(rep)) + "|"]
    for k, th in enumerate(REPORT_THETA):
        cells = []
        for r in rep:
            row = r["rows"][k]
            vc, e = row["var_cosine"], row["albedo"]
            cells.append("0" if vc <= 1e-6 * e * e else f"{vc:.3e}")
            cells.append(ratio_text(vc, row["var_fit"], e))
            cells.append(ratio_text(vc, row["var_eon"], e))
        lines.append(f"| {th:.0f}° | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def screen(cli, log):
    """Wolff and Burley: the per-point optimum CLTC at REPORT_THETA, an upper bound on what
    a fitted sampler could gain over the cosine, and the cosine's relative variance."""
    grid = Grid(*FIT_GRID)
    mus = [np.cos(np.radians(th)) for th in REPORT_THETA]
    out = {}
    for bsdf, params in (
        ("wolff", []),
        ("wolff", [("int_ior", "2.4")]),
        ("burley", [("roughness", "0.3")]),
        ("burley", [("roughness", "1")]),
    ):  # Burley: before its fit, the case for one
        F = cli.f(bsdf, params, mus, grid, f"screen{FIT_GRID[0]}")
        x = x_of_params((1.0, 0.0, 1.0, 0.0, 1e-6))
        ratios, relative = [], []
        for _mu, f in zip(mus, F):
            fc = f * grid.wo[:, 2]
            vc = cosine_variance(fc, grid)
            e = fc.sum() * grid.weight
            x, v = optimum(fc, grid, [x])
            ratios.append(ratio_text(vc, max(v, 0.0), e))
            relative.append(f"{vc / e**2:.2e}")
        label = " ".join([bsdf] + [f"{k}={v}" for k, v in params])
        out[label] = dict(optimum_ratio=ratios, cosine_relative_variance=relative)
        log(
            f"  {label}: at θi = {REPORT_THETA}: optimum ratio cosine/CLTC {ratios}; Var/E² under the cosine {relative}"
        )
    return out


# ---------------------------------------------------------------- the Rust file ------------


def rust_file(fitted):
    """`rust/brdf/src/sampler_fits.rs`: one `CltcFit` per model."""
    lines = [
        "//! Generated by `validation/generators/fit_samplers.py`; do not edit (rerun it).",
        "//! The importance samplers fitted to the rough models: clipped linearly transformed cosines",
        "//! with a uniform share ([`CltcFit`], `rust/brdf/src/cltc.rs`) whose five parameters are",
        f"//! polynomials of degree {DEG_MU} in μ = cos θi and {DEG_T} in the model's roughness variable t,",
        "//! fitted to minimise the exact variance of the sampling weight f cos θo / pdf (ρ = 1)",
        f"//! over θi ∈ {{{', '.join(f'{t:g}' for t in FIT_THETA)}}}° and",
        f"//! t ∈ {{{', '.join(f'{t:g}' for t in FIT_T)}}} (`docs/sampling.md`).",
        "",
        "use super::cltc::CltcFit;",
    ]
    for model, C, note in fitted:
        shape = model.form.shape
        Cr = np.asarray(C).reshape(shape)
        lines += [
            "",
            f"/// {model.label}: {note}",
            f"pub const {model.name}: CltcFit<{shape[1]}, {shape[2]}> = CltcFit {{",
            "    coefficients: [",
        ]
        for k in range(5):
            lines.append(f"        // {NAMES[k]}")
            lines.append("        [")
            for i in range(shape[1]):
                lines.append("            [" + ", ".join(f"{float(c):.10e}" for c in Cr[k, i]) + "],")
            lines.append("        ],")
        free = ", ".join("true" if k in model.form.free_at_normal else "false" for k in range(5))
        lines += ["    ],", f"    free_at_normal: [{free}],", "};"]
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- main ---------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--matte", default="target/release/matte", help="the matte CLI (for van Ginneken's f)")
    ap.add_argument("--cache", default="target/fit_samplers", help="f on the quadrature grids and the fits")
    ap.add_argument("--out", default="rust/brdf/src/sampler_fits.rs")
    ap.add_argument("--report", default=None, help="also write the tables (Markdown) and the fits (JSON) here")
    ap.add_argument("--no-screen", action="store_true", help="skip the Wolff and Burley screening")
    args = ap.parse_args()
    log = lambda s: print(s, file=sys.stderr, flush=True)  # noqa: E731
    cli = Cli(args.matte, args.cache)
    fitted, text, summary, own = [], [], {}, {}
    for model in models(cli):
        C, V, Vc, J, J_opt = fit(model, cli, args.cache, log)
        own[model.name] = C
        loss = np.exp(J - J_opt)
        log(
            f"{model.label}: {model.form.size()} coefficients; mean variance over the per-point optima "
            f"×{loss:.3f} (geometric mean over the fitting grid)"
        )
        if model.samples_with:
            C = own[model.samples_with]
            loss = np.exp(model.objective.value(C, penalty=0.0) - J_opt)
            log(f"{model.label} sampled with {model.samples_with}'s fit: ×{loss:.3f} of the per-point optima")
        worst, worst_far = dense_check(model, C, log)
        rep = report(model, C, log)
        table = markdown(model, rep)
        text.append(f"### {model.label}\n\n{table}\n")
        print(f"\n### {model.label}\n\n{table}\n", flush=True)
        note = f"t = {model.t_text}; geometric-mean variance ×{loss:.3f} of the per-point optima."
        fitted.append((model, C, note))
        summary[model.name] = dict(
            coefficients=np.asarray(C).tolist(),
            loss=loss,
            report=rep,
            worst_ratio=worst[0],
            worst_ratio_at=worst[1],
            worst_ratio_45=worst_far[0],
        )
        if model.samples_with:
            summary[model.name]["samples_with"] = model.samples_with
    # Do van Ginneken's two shadowing options need fits of their own? Each one's fitting
    # objective under the other's coefficients.
    by_name = {m.name: m for m, _, _ in fitted}
    a, b = "GINNEKEN", "GINNEKEN_HEIGHT_CORRELATED"
    for x, y in ((a, b), (b, a)):
        mx = by_name[x]
        cost = np.exp(mx.objective.value(own[y], penalty=0.0) - mx.objective.value(own[x], penalty=0.0))
        summary[f"{x}_with_{y}"] = cost
        log(f"{mx.label} sampled with the other shadowing's fit: geometric-mean variance ×{cost:.3f}")
    if not args.no_screen:
        summary["screen"] = screen(cli, log)
    with open(args.out, "w") as f:
        f.write(rust_file([x for x in fitted if not x[0].samples_with]))
    log(f"wrote {args.out}")
    if args.report:
        os.makedirs(args.report, exist_ok=True)
        with open(os.path.join(args.report, "fit_samplers.md"), "w") as f:
            f.write("\n".join(text))
        with open(os.path.join(args.report, "fit_samplers.json"), "w") as f:
            json.dump(summary, f, indent=1, default=float)


if __name__ == "__main__":
    main()
