"""Independent numpy reference for the EON importance sampler (CLTC + uniform).

Model: Portsmouth, Kutz & Hill, "EON: A practical energy-preserving rough
diffuse BRDF", JCGT 14(1), 2025 (arXiv:2410.18026); fitted constants as in
github.com/portsmouth/EON-diffuse, main.glsl (ltc_coeffs, sample_EON).
Written from the maths of the paper's section 4, not transcribed from that code; a
second implementation beside matte's (rust/brdf/src/cltc.rs, rust/brdf/src/models/eon.rs), in float64.
matte's two choices are parameters here: the uniform component's roughness factor
r**UNIFORM_EXPONENT (the paper: 0.1, matte: 1/8) and d clamped to <= 0 (CLAMP_D).

Convention (Mitsuba): local shading frame, normal = +z.
  wi : the FIXED direction (towards viewer / previous vertex), shape (..., 3)
  wo : the SAMPLED / queried direction,                          shape (..., 3)
The paper/GLSL names are swapped (there wo_local is fixed, wi_local sampled).

Public API (vectorised, broadcasting over leading dims):
  sample(wi, u1, u2, r) -> (wo, pdf)     pdf = solid-angle density of wo
  pdf(wi, wo, r)        -> pdf
Invalid input (wi.z <= 0) gives wo = 0 and pdf = 0.
"""

import numpy as np

INV_PI = 1.0 / np.pi
INV_2PI = 0.5 / np.pi


# ---------------------------------------------------------------- fits ------
def ltc_coeffs(mu, r):
    """Non-trivial entries of M = [[a,0,b],[0,c,0],[d,0,1]] (fixed-dir cos mu)."""
    a = 1.0 + r * (0.303392 - 0.518982 * mu + 0.111709 * mu**2 + (-0.276266 + 0.335918 * mu) * r)
    b = r * (-1.16407 + 1.15859 * mu + (0.150815 - 0.150105 * mu) * r) / (mu**3 - 1.43545)
    c = 1.0 + r * (0.20013 - 0.506373 * mu + 0.261777 * mu**2)
    d = r * (0.540852 - 1.01625 * mu + 0.475392 * mu**2) / (mu**2 + 0.0725628 * mu - 1.0743)
    if CLAMP_D:
        d = np.minimum(d, 0.0)
    return a, b, c, d


UNIFORM_EXPONENT = 0.125
CLAMP_D = True


def uniform_prob(mu, r):
    """P_u(mu, r): probability of the uniform-hemisphere technique."""
    return np.power(r, UNIFORM_EXPONENT) * (0.162925 - 0.372058 * mu + 0.538233 * mu**2 - 0.290822 * mu**3)


def clip_fraction(d):
    """s = projected-disk area fraction kept by the clip plane d*x + z >= 0."""
    return 0.5 * (1.0 + 1.0 / np.sqrt(1.0 + d * d))


def _frame_x(wi):
    """Unit azimuth of the fixed direction (LTC +x axis); (1,0) if wi ~ normal."""
    l2 = wi[..., 0] ** 2 + wi[..., 1] ** 2
    ok = l2 > 0.0
    inv = np.where(ok, 1.0 / np.sqrt(np.where(ok, l2, 1.0)), 0.0)
    cx = np.where(ok, wi[..., 0] * inv, 1.0)
    cy = np.where(ok, wi[..., 1] * inv, 0.0)
    return cx, cy  # X = (cx, cy, 0), Y = z x X = (-cy, cx, 0)


# ----------------------------------------------------------------- pdf ------
def cltc_pdf_ltcframe(w, a, b, c, d):
    """Clipped-LTC density of w (already in LTC frame), 0 outside the support."""
    det = c * (a - b * d)  # det M  (> 0 here)
    qx = c * (w[..., 0] - b * w[..., 2])  # q = adj(M) w = det * M^-1 w
    qy = (a - b * d) * w[..., 1]
    qz = c * (a * w[..., 2] - d * w[..., 0])
    q2 = qx * qx + qy * qy + qz * qz
    s = clip_fraction(d)
    # D_o(q/|q|) * det(M^-1) / |M^-1 w|^3 = (det/|q|^2)^2 * q_z / (pi s)
    p = (det / q2) ** 2 * np.maximum(qz, 0.0) / (np.pi * s)
    return np.where(w[..., 2] > 0.0, p, 0.0)


def pdf(wi, wo, r):
    wi = np.asarray(wi, float)
    wo = np.asarray(wo, float)
    r = np.asarray(r, float)
    mu = wi[..., 2]
    valid = (mu > 0.0) & (wo[..., 2] > 0.0)
    mu_c = np.clip(mu, 0.0, 1.0)
    a, b, c, d = ltc_coeffs(mu_c, r)
    cx, cy = _frame_x(wi)
    w = np.stack([cx * wo[..., 0] + cy * wo[..., 1], -cy * wo[..., 0] + cx * wo[..., 1], wo[..., 2]], axis=-1)
    pc = cltc_pdf_ltcframe(w, a, b, c, d)
    pu = uniform_prob(mu_c, r)
    return np.where(valid, pu * INV_2PI + (1.0 - pu) * pc, 0.0)


# -------------------------------------------------------------- sample ------
def sample(wi, u1, u2, r, sign_aware=True):
    """One-sample mixture: uniform hemisphere w.p. P_u, else clipped LTC.

    u1 selects the technique and is then rescaled and reused; u2 is azimuth.
    sign_aware=False reproduces the reference GLSL, which assumes d <= 0
    (d is slightly positive for mu > ~0.99988; see notes).
    """
    wi = np.asarray(wi, float)
    u1 = np.asarray(u1, float)
    u2 = np.asarray(u2, float)
    r = np.asarray(r, float)
    shape = np.broadcast_shapes(wi.shape[:-1], u1.shape, u2.shape, r.shape)
    wi = np.broadcast_to(wi, shape + (3,))
    u1 = np.broadcast_to(u1, shape)
    u2 = np.broadcast_to(u2, shape)
    r = np.broadcast_to(r, shape)
    mu = wi[..., 2]
    valid = mu > 0.0
    mu_c = np.clip(mu, 0.0, 1.0)
    a, b, c, d = ltc_coeffs(mu_c, r)
    pu = uniform_prob(mu_c, r)
    pc = 1.0 - pu

    use_u = u1 < pu  # strict: pu == 0 at r == 0
    v1 = np.where(use_u, u1 / np.where(pu > 0, pu, 1.0), (u1 - pu) / pc)
    v1 = np.clip(v1, 0.0, 1.0)
    phi = 2.0 * np.pi * u2

    # uniform hemisphere: cos(theta) = v1
    sz = np.sqrt(np.maximum(1.0 - v1 * v1, 0.0))
    wu = np.stack([sz * np.cos(phi), sz * np.sin(phi), v1], axis=-1)

    # clipped cosine in the LTC pre-image: uniform disk point, then each
    # horizontal chord [-L, L] squashed affinely onto the kept part
    # [-L, vz L] (d <= 0) or [-vz L, L] (d > 0).
    R = np.sqrt(v1)
    x0 = R * np.cos(phi)
    y = R * np.sin(phi)
    s = clip_fraction(d)
    L = np.sqrt(np.maximum(1.0 - y * y, 0.0))
    sgn = np.where(d > 0.0, 1.0, -1.0) if sign_aware else -1.0
    x = sgn * ((1.0 - s) * L + s * x0)
    hz = np.sqrt(np.maximum(1.0 - x * x - y * y, 0.0))
    # M h, then from LTC frame to shading frame
    mx, my, mz = a * x + b * hz, c * y, d * x + hz
    cx, cy = _frame_x(wi)
    wc = np.stack([cx * mx - cy * my, cy * mx + cx * my, mz], axis=-1)
    wc /= np.linalg.norm(wc, axis=-1, keepdims=True)

    wo = np.where(use_u[..., None], wu, wc)
    # mixture pdf; evaluated through pdf() for both branches so that the value
    # returned by sample() is bit-identical to pdf(wi, wo) (the reference uses
    # the forward Jacobian |M h|^3 / det M in the CLTC branch instead; it is
    # the same number up to rounding).
    p = pdf(wi, wo, r)
    wo = np.where(valid[..., None], wo, 0.0)
    return wo, np.where(valid, p, 0.0)


def cltc_forward_pdf(wi, u1, u2, r):
    """Forward (sampling-side) CLTC density |M h|^3 / det M * h_z/(pi s), for
    cross-checking the inverse formula used in pdf(). u1 here is the already
    rescaled CLTC random number."""
    mu = np.clip(np.asarray(wi, float)[..., 2], 0.0, 1.0)
    a, b, c, d = ltc_coeffs(mu, r)
    R = np.sqrt(u1)
    phi = 2.0 * np.pi * u2
    x0, y = R * np.cos(phi), R * np.sin(phi)
    s = clip_fraction(d)
    L = np.sqrt(np.maximum(1.0 - y * y, 0.0))
    x = np.where(d > 0, 1.0, -1.0) * ((1.0 - s) * L + s * x0)
    hz = np.sqrt(np.maximum(1.0 - x * x - y * y, 0.0))
    m = np.stack([a * x + b * hz, c * y, d * x + hz], axis=-1)
    ln = np.linalg.norm(m, axis=-1)
    return hz / (np.pi * s) * ln**3 / (c * (a - b * d))


# ---------------------------------------------------------- EON BRDF --------
def f_eon(rho, r, wi, wo):
    """EON BRDF (exact FON albedo), used only for the weight check."""
    k1 = 0.5 - 2.0 / (3.0 * np.pi)
    k2 = 2.0 / 3.0 - 28.0 / (15.0 * np.pi)
    mi, mo = wi[..., 2], wo[..., 2]
    sv = np.sum(wi * wo, -1) - mi * mo
    st = np.where(sv > 0, sv / np.maximum(np.maximum(mi, mo), 1e-30), sv)
    AF = 1.0 / (1.0 + k1 * r)

    def efon(m):
        m = np.clip(m, 1e-7, 1.0)
        si = np.sqrt(1 - m * m)
        G = si * (np.arccos(m) - si * m) + 2.0 / 3.0 * ((si / m) * (1 - si**3) - si)
        return AF + r * AF * INV_PI * G

    avg = AF * (1 + k2 * r)
    rms = rho * rho * avg / (1 - rho * (1 - avg))
    fss = rho * INV_PI * AF * (1 + r * st)
    fms = rms * INV_PI * np.maximum(1e-7, 1 - efon(mo)) * np.maximum(1e-7, 1 - efon(mi)) / max(1e-7, 1 - avg)
    return fss + fms


# ------------------------------------------------------------ self-check ----
def _dir(theta_deg, phi_deg=0.0):
    t, p = np.radians(theta_deg), np.radians(phi_deg)
    return np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])


def _grid(nz, nphi):
    """Midpoint grid in (z = cos theta, phi); weight dz*dphi = d(omega)."""
    z = (np.arange(nz) + 0.5) / nz
    ph = (np.arange(nphi) + 0.5) / nphi * 2 * np.pi
    Z, P = np.meshgrid(z, ph, indexing="ij")
