"""van Ginneken's slope integral in numpy, vectorised over configurations: the same
semi-analytic scheme as `rust/brdf/src/models/ginneken/slope_integral.rs` (`SlopeIntegrator`), for the
prototype fits of `fit_slope_integral.py`.

    I(μi, μo, Δφ) = ∬ P22(p, q) (μi − p·wi)⁺ (μo − p·wo)⁺ / √(1 + p² + q²) dp dq

Polar slope coordinates (t, ψ): the ψ-integral of the two clamped cosines is closed form
(`angular`), the t-integral over the Rayleigh density is Gauss–Legendre on the pieces between
the clamping onsets t = cot θ (substitution t = t₀ + (t₁ − t₀) w² on the later pieces), cut at
√80 m. Also: the unclamped closed form, the visibility term and f as `accuracy.rs` measures it.
"""

import math

import numpy as np

TRUNCATION = math.sqrt(80.0)
TAU = 2 * math.pi


def _gl01(n):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1), 0.5 * w


def _product_primitive(a1, b1, a2, b2, phi):
    """An antiderivative in ψ of (a1 − b1 cos ψ)(a2 − b2 cos(ψ − φ)), expanded with
    cos ψ cos(ψ−φ) = ½[cos φ + cos(2ψ − φ)]."""
    k0 = a1 * a2 + 0.5 * b1 * b2 * np.cos(phi)

    def prim(x):
        return k0 * x - a1 * b2 * np.sin(x - phi) - a2 * b1 * np.sin(x) + 0.25 * b1 * b2 * np.sin(2 * x - phi)

    return prim


def _half_width(a, b):
    """acos(a/b) where b > a (the half-width of the arc where a − b cos ψ changes sign), else 0."""
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(b > a, a / np.where(b > 0, b, 1.0), 1.0)
    return np.arccos(np.clip(r, -1.0, 1.0))


def _arcs_overlap(prim, s1, l1, s2, l2):
    """The integral (by its antiderivative) over the intersection of the arcs (start, length),
    the second shifted by −2π, 0 and 2π."""
    total = 0.0
    for k in (-1, 0, 1):
        lo, hi = np.maximum(s1, s2 + k * TAU), np.minimum(s1 + l1, s2 + l2 + k * TAU)
        total = total + np.where(hi > lo, prim(hi) - prim(lo), 0.0)
    return total


def angular(mu_i, s_i, mu_o, s_o, phi, t):
    """(1/2π) ∫ (a1 − b1 cos ψ)⁺ (a2 − b2 cos(ψ − φ))⁺ dψ, broadcast over all arguments."""
    a1, b1, a2, b2 = mu_i, t * s_i, mu_o, t * s_o
    d1, d2 = _half_width(a1, b1), _half_width(a2, b2)
    return _arcs_overlap(_product_primitive(a1, b1, a2, b2, phi), d1, TAU - 2 * d1, phi + d2, TAU - 2 * d2) / TAU


def slope_integral(m, mu_i, mu_o, phi, nodes=48, derivative=False):
    """I (and ∂I/∂m if `derivative`) at arrays mu_i, mu_o, phi (broadcast), scalar or array m."""
    m, mu_i, mu_o, phi = np.broadcast_arrays(*(np.asarray(v, float) for v in (m, mu_i, mu_o, phi)))
    s_i = np.sqrt(np.maximum(1 - mu_i**2, 0))
    s_o = np.sqrt(np.maximum(1 - mu_o**2, 0))
    t_max = TRUNCATION * m
    with np.errstate(divide="ignore"):
        ci = np.where(s_i > 0, mu_i / np.where(s_i > 0, s_i, 1), np.inf)
        co = np.where(s_o > 0, mu_o / np.where(s_o > 0, s_o, 1), np.inf)
    b = np.sort(np.stack([np.zeros_like(m), np.minimum(ci, t_max), np.minimum(co, t_max), t_max]), axis=0)
    x, w = _gl01(nodes)
    sh = (-1,) + (1,) * m.ndim
    x, w = x.reshape(sh), w.reshape(sh)
    inv_m2 = 1 / m**2
    args = [a[None] for a in (mu_i, s_i, mu_o, s_o, phi)]
    total, dtotal = 0.0, 0.0
    for k in range(3):
        t0, t1 = b[k][None], b[k + 1][None]
        length = t1 - t0
        if k == 0:
            t, wt = t0 + length * x, length * w
        else:
            t, wt = t0 + length * x * x, 2 * length * x * w
        dens = t * inv_m2[None] * np.exp(-0.5 * t * t * inv_m2[None]) / np.sqrt(1 + t * t)
        v = dens * angular(*args, t) * wt
        total = total + v.sum(0)
        if derivative:
            dtotal = dtotal + (v * (t * t * inv_m2[None] - 2) / m[None]).sum(0)
    return (total, dtotal) if derivative else total


def expectations(m, nodes=200):
    """E[1/√(1+t²)] and ½E[t²/√(1+t²)] for the Rayleigh slope magnitude t (scale m)."""
    x, w = _gl01(nodes)
    m = np.asarray(m, float)[..., None]
    t = TRUNCATION * m * x
    dens = t / m**2 * np.exp(-0.5 * t * t / m**2) * TRUNCATION * m * w
    return (dens / np.sqrt(1 + t * t)).sum(-1), 0.5 * (dens * t * t / np.sqrt(1 + t * t)).sum(-1)


def unclamped(m, mu_i, mu_o, cos_phi, e=None):
    e1, e2 = expectations(m) if e is None else e
    s_i, s_o = np.sqrt(np.maximum(1 - mu_i**2, 0)), np.sqrt(np.maximum(1 - mu_o**2, 0))
    return mu_i * mu_o * e1 + s_i * s_o * cos_phi * e2


_erfc = np.vectorize(math.erfc)


def mu_lambda(mu, s, m):
    with np.errstate(divide="ignore", invalid="ignore"):
        a = mu / (m * s)
        v = 0.5 * (math.sqrt(2 / math.pi) * m * s * np.exp(-0.5 * a * a) - mu * _erfc(np.minimum(a, 40) / math.sqrt(2)))
    return np.where((s > 0) & (a <= 12), np.maximum(v, 0), 0.0)


def visibility_denominator(mu_i, mu_o, m, cos_phi, shadowing="vginneken"):
    s_i, s_o = np.sqrt(1 - mu_i**2), np.sqrt(1 - mu_o**2)
    li, lo = mu_lambda(mu_i, s_i, m), mu_lambda(mu_o, s_o, m)
    if shadowing == "height_correlated":
        return mu_i * mu_o + mu_o * li + mu_i * lo
    phi = np.arccos(np.clip(cos_phi, -1, 1))
    alpha = 4.41 * phi / (4.41 * phi + 1)
    i_min = mu_i <= mu_o
    mu_min, ml_min = np.where(i_min, mu_i, mu_o), np.where(i_min, li, lo)
    mu_max, ml_max = np.where(i_min, mu_o, mu_i), np.where(i_min, lo, li)
    return mu_min * mu_max + mu_max * ml_min + alpha * mu_min * ml_max


def r3_configurations(max_theta_deg, samples):
    """`accuracy.rs`'s R3 sequence: (θi, θo, Δφ) in degrees."""
    g = 1.2207440846057595
    alpha = np.array([1 / g, 1 / g**2, 1 / g**3])
    k = np.arange(samples, dtype=float)[:, None] + 1
    x = np.modf(0.5 + alpha[None] * k)[0]
    return x[:, 0] * max_theta_deg, x[:, 1] * max_theta_deg, x[:, 2] * 180.0


def eval_reference(m, ti_deg, to_deg, ph_deg, shadowing="vginneken"):
    """f for ρ = 1, as `Ginneken::eval_reference` (directions built like `accuracy.rs`)."""
    ti, to, ph = np.radians(ti_deg), np.radians(to_deg), np.radians(ph_deg)
    wi = np.stack([np.sin(ti), np.zeros_like(ti), np.cos(ti)])
    wo = np.stack([np.sin(to) * np.cos(ph), np.sin(to) * np.sin(ph), np.cos(to)])
    si, so = np.hypot(wi[0], wi[1]), np.hypot(wo[0], wo[1])
    cos_phi = np.where(
        si * so > 1e-300, np.clip((wi[0] * wo[0] + wi[1] * wo[1]) / np.maximum(si * so, 1e-300), -1, 1), 1.0
    )
    integral = slope_integral(m, wi[2], wo[2], np.arccos(cos_phi))
    return integral / (math.pi * visibility_denominator(wi[2], wo[2], m, cos_phi, shadowing)), wi, wo


# ---------------------------------------------------------------------------------------------
# The split I = rest + K. With X = p·ŵi the slope component along wi's azimuth,
# (μ − p·w)⁺ = (μ − p·w) + s (X − cot θ)⁺ for each direction; expanding the product leaves
#   * terms with one clamp, whose expectations are 1-D functions of one direction, and
#   * K = E[w (p·wi − μi)⁺ (p·wo − μo)⁺] (both facets facing away: a wedge in slope space).
# Regrouped so that every term is ≥ 0 (no cancellation, see fit_slope_integral.py):
#   rest = μo P0(θi) + μi P0(θo) + so P1(θi) + si P1(θo) + (1 + cos Δφ) si so (H(θi) + H(θo))
# with, for X ~ N(0, m²) and h(X) = E_Z[1/√(1 + X² + Z²)], Z ~ N(0, m²), c = cot θ:
#   P0 = E[h (μ − s X); 0 < X < c],  P1 = E[h X (μ − s X); 0 < X < c],  H = E[h X min(X, c); X > 0].
# ---------------------------------------------------------------------------------------------


def _gl(n, a, b):
    x, w = np.polynomial.legendre.leggauss(n)
    a, b = np.asarray(a, float)[..., None], np.asarray(b, float)[..., None]
    return a + (b - a) * (x + 1) / 2, (b - a) * w / 2


def h_slope(X, m, n=160):
    """E_Z[1/√(1+X²+Z²)] for Z ~ N(0, m²)."""
    z, wz = _gl(n, 0.0, TRUNCATION * m)
    dens = 2 * np.exp(-0.5 * z * z / m**2) / (math.sqrt(2 * math.pi) * m)
    X = np.asarray(X)[..., None]
    return (wz * dens / np.sqrt(1 + X * X + z * z)).sum(-1)


def _phi_m(X, m):
    return np.exp(-0.5 * X * X / m**2) / (math.sqrt(2 * math.pi) * m)


def direction_functions(m, mu, n=64):
    """(P0, P1, H) at cosines mu (array), roughness m (scalar)."""
    mu = np.asarray(mu, float)
    s = np.sqrt(1 - mu * mu)
    cot = np.minimum(np.where(s > 0, mu / np.where(s > 0, s, 1), np.inf), TRUNCATION * m)
    X, wx = _gl(n, 0.0, cot)
    base = wx * h_slope(X, m) * _phi_m(X, m)
    P0 = (base * (mu[..., None] - s[..., None] * X)).sum(-1)
    P1 = (base * X * (mu[..., None] - s[..., None] * X)).sum(-1)
    X2, wx2 = _gl(n, cot, TRUNCATION * m)
    H = (base * X * X).sum(-1) + cot * (wx2 * h_slope(X2, m) * _phi_m(X2, m) * X2).sum(-1)
    return P0, P1, H


def normalized_direction_functions(m, mu):
    """(P0/μ², P1/μ³, H/μ): finite and non-zero from μ = 0 to 1, what the fits tabulate."""
    P0, P1, H = direction_functions(m, mu)
    return np.stack([P0 / mu**2, P1 / mu**3, H / mu])


def rest_from_normalized(Fi, Fo, mu_i, mu_o, cos_phi):
    s_i, s_o = np.sqrt(1 - mu_i**2), np.sqrt(1 - mu_o**2)
    return (
        mu_o * mu_i**2 * Fi[0]
        + mu_i * mu_o**2 * Fo[0]
        + s_o * mu_i**3 * Fi[1]
        + s_i * mu_o**3 * Fo[1]
        + (1 + cos_phi) * s_i * s_o * (mu_i * Fi[2] + mu_o * Fo[2])
    )


def wedge_integral(m, mu_i, mu_o, phi, nodes=48):
    """K = E[w (p·wi − μi)⁺ (p·wo − μo)⁺] (the same scheme as `slope_integral`: the angular
    integral of the same product over the two arcs where both factors are negative)."""
    m, mu_i, mu_o, phi = np.broadcast_arrays(*(np.asarray(v, float) for v in (m, mu_i, mu_o, phi)))
    s_i, s_o = np.sqrt(np.maximum(1 - mu_i**2, 0)), np.sqrt(np.maximum(1 - mu_o**2, 0))
    t_max = TRUNCATION * m
    with np.errstate(divide="ignore"):
        ci = np.where(s_i > 0, mu_i / np.where(s_i > 0, s_i, 1), np.inf)
        co = np.where(s_o > 0, mu_o / np.where(s_o > 0, s_o, 1), np.inf)
    t0 = np.minimum(np.maximum(ci, co), t_max)  # both clamp only beyond both onsets
    x, w = _gl01(nodes)
    sh = (-1,) + (1,) * m.ndim
    x, w = x.reshape(sh), w.reshape(sh)
    L = (t_max - t0)[None]
    t, wt = t0[None] + L * x * x, 2 * L * x * w
    a1, b1, a2, b2 = mu_i[None], t * s_i[None], mu_o[None], t * s_o[None]
    ph = phi[None]
    # The arcs [off − δ, off + δ] where both factors are negative (δ = 0: no arc).
    d1, d2 = _half_width(a1, b1), _half_width(a2, b2)
    ang = _arcs_overlap(_product_primitive(a1, b1, a2, b2, ph), -d1, 2 * d1, ph - d2, 2 * d2)
    inv_m2 = 1 / m[None] ** 2
    dens = t * inv_m2 * np.exp(-0.5 * t * t * inv_m2) / np.sqrt(1 + t * t)
    return (dens * ang / TAU * wt).sum(0)
