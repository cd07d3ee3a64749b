#!/usr/bin/env python3
"""Prints Tables 1, 2 and 3 of docs/models.md#reference-values, the oracle of
tests/kernels/reference_tables.rs, from an independent float64 numpy implementation of the
formulas as docs/models.md states them. It does not import or call matte. Run it by hand
with the venv's Python from the repository root:

    .venv/bin/python tests/kernels/reference_tables/generate.py           # print the tables
    .venv/bin/python tests/kernels/reference_tables/generate.py --check   # compare

Without a flag it prints the three tables in the Markdown layout of docs/models.md (paste
them under "### Table 1" etc.). `--check` parses the tables of docs/models.md and the arrays of
tests/kernels/reference_tables.rs and reports every cell that differs from this script's value
at the printed digits, then does the same for the numbers docs/models.md quotes in its text
(Fresnel averages, Wolff's E(0°), Oren–Nayar's grazing maximum, van Ginneken's α(φ)); it
exits 1 if any differs. Either way it takes 10–30 s on 2 cores (more when they are busy), most
of it the van Ginneken albedos of Table 2.

The numerical choices are the ones docs/models.md names:

* Table 1 (f at ρ = 0.8): closed forms in f64; van Ginneken's slope integral I by the naive
  2-D midpoint rule on [−7m, 7m]² with 800² cells.
* Table 2 (albedo at ρ = 1): 96-point Gauss–Legendre in μo on [0, 1] × 192 azimuth midpoints
  on [0, 2π) for the closed forms; for van Ginneken 32 Gauss–Legendre nodes in μo × 48
  azimuth midpoints on [0, π) (f is even in Δφ), each with a 160² midpoint grid for I; no 89°
  column.
* Table 3 (qualitative Oren–Nayar, ρ = 1): A, B in closed form, E(0°) and E(89.9°) by the
  closed-form quadrature of Table 2.
* Wolff's F_dr,ext and F_dr,int: 2∫₀¹ F(μ) μ dμ by 400-node Gauss–Legendre, the internal one
  split at the critical angle (total internal reflection above it).

Four printed digits sit on a rounding boundary of these quadratures (all within the tests'
tolerances, all reproduced as printed with the choices above):

* Table 1, vG m = 0.3 at 75/75/180 and m = 0.5 at 60/60/180: 0.0878462 and 0.1118152 on the
  800² grid (0.08785, 0.11182 as printed); 4000² cells give 0.0878434 and 0.1118136 (0.08784,
  0.11181), 3e-5 relative lower, inside the ~1e-4 the doc claims for the 800² grid.

* Table 2, vG m = 0.3 at 80°: 0.926357 with 48 azimuth midpoints on [0, π); 0.926335 (0.9263)
  with 48 on [0, 2π). A finer rule (64 × 192 on [0, 2π), 400² inner cells) gives 0.926367, so
  0.9264 is the right rounding and [0, π) is the reading of "48 azimuth midpoints" that
  reproduces it.
* Table 3, E(89.9°) at σ = 0.5: the quadrature above gives 0.949751 (0.9498, as printed); a
  converged one (400 × 400 Gauss–Legendre split at θo = θi and at Δφ = ±π/2) gives 0.949740,
  i.e. 0.9497. Table 3's E(89.9°) column is not a test oracle.
"""

import argparse
import re
import sys
from math import erfc
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[3]
DOC = ROOT / "docs" / "models.md"
TEST = ROOT / "tests" / "kernels" / "reference_tables.rs"
PI = np.pi

# ---------------------------------------------------------------------------------------------
# Directions. wi at φ = 0, wo at φ = Δφ; θ in radians.


def directions(ti, to, dphi):
    """Broadcasting arrays: (μi, μo, sin θi, sin θo, cos Δφ, s = wi·wo − μi μo)."""
    ti, to, dphi = np.broadcast_arrays(*(np.asarray(x, dtype=np.float64) for x in (ti, to, dphi)))
    mi, mo, si, so, c = np.cos(ti), np.cos(to), np.sin(ti), np.sin(to), np.cos(dphi)
    return mi, mo, si, so, c, si * so * c


# ---------------------------------------------------------------------------------------------
# The models: f(θi, θo, Δφ; ρ) in 1/sr, exactly as docs/models.md writes them.


def lambert(rho):
    return lambda ti, to, dphi: np.full(np.broadcast(ti, to, dphi).shape, rho / PI)


def qon(sigma, rho):
    """Oren–Nayar qualitative (their eq. 30): A + B max(0, cos Δφ) sin α tan β."""
    s2 = sigma * sigma
    a, b = 1 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09)

    def f(ti, to, dphi):
        ti, to, dphi = np.broadcast_arrays(ti, to, dphi)
        alpha, beta = np.maximum(ti, to), np.minimum(ti, to)
        return rho / PI * (a + b * np.maximum(0.0, np.cos(dphi)) * np.sin(alpha) * np.tan(beta))

    return f


def full_on(sigma, rho, second_bounce=True):
    """Oren–Nayar full model: C1–C3 (eqs. 27–29) plus the two-bounce term (eq. 37)."""
    s2 = sigma * sigma

    def f(ti, to, dphi):
        ti, to, dphi = np.broadcast_arrays(ti, to, dphi)
        alpha, beta = np.maximum(ti, to), np.minimum(ti, to)
        # Signed cos Δφ, 0 when either direction is the normal.
        c = np.where((ti == 0) | (to == 0), 0.0, np.cos(dphi))
        c1 = 1 - 0.5 * s2 / (s2 + 0.33)
        c2 = 0.45 * s2 / (s2 + 0.09) * np.where(c >= 0, np.sin(alpha), np.sin(alpha) - (2 * beta / PI) ** 3)
        c3 = 0.125 * s2 / (s2 + 0.09) * (4 * alpha * beta / PI**2) ** 2
        f1 = rho / PI * (c1 + c * c2 * np.tan(beta) + (1 - np.abs(c)) * c3 * np.tan((alpha + beta) / 2))
        f2 = 0.17 * rho**2 / PI * s2 / (s2 + 0.13) * (1 - c * (2 * beta / PI) ** 2)
        return f1 + f2 if second_bounce else f1

    return f


C1_EON = 0.5 - 2 / (3 * PI)
C2_EON = 2 / 3 - 28 / (15 * PI)


def fon(r, rho):
    """Fujii's improved Oren–Nayar, EON's single-scattering lobe."""
    a_f = 1 / (1 + C1_EON * r)

    def f(ti, to, dphi):
        mi, mo, _, _, _, s = directions(ti, to, dphi)
        t = np.where(s > 0, np.maximum(mi, mo), 1.0)
        return rho / PI * a_f * (1 + r * s / t)

    return f


def eon_ef(mu, r):
    """FON's exact albedo for ρ = 1: E_F(μ) = A_F + (B_F/π) G(μ)."""
    a_f = 1 / (1 + C1_EON * r)
    b_f = r * a_f
    mu = np.asarray(mu, dtype=np.float64)
    s = np.sqrt(1 - mu * mu)
    g = s * (np.arccos(mu) - s * mu) + 2 / 3 * ((s / mu) * (1 - s**3) - s)
    return a_f + b_f / PI * g


def eon(r, rho):
    """EON = FON + the multiple-scattering lobe (Portsmouth, Kutz & Hill 2025)."""
    a_f = 1 / (1 + C1_EON * r)
    ef_mean = a_f * (1 + C2_EON * r)
    rho_ms = rho**2 * ef_mean / (1 - rho * (1 - ef_mean))
    single = fon(r, rho)

    def f(ti, to, dphi):
        mi, mo, *_ = directions(ti, to, dphi)
        f_ms = rho_ms / PI * (1 - eon_ef(mi, r)) * (1 - eon_ef(mo, r)) / (1 - ef_mean)
        return single(ti, to, dphi) + f_ms

    return f


def fresnel(c, n):
    """Unpolarised Fresnel reflectance, Cook–Torrance g form; 1 under total internal reflection."""
    c = np.asarray(c, dtype=np.float64)
    g2 = n * n - 1 + c * c
    g = np.sqrt(np.maximum(g2, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        f = 0.5 * (g - c) ** 2 / (g + c) ** 2 * (1 + (c * (g + c) - 1) ** 2 / (c * (g - c) + 1) ** 2)
    return np.where(g2 < 0, 1.0, f)


def gauss_legendre(n, a, b):
    x, w = np.polynomial.legendre.leggauss(n)
    return a + (b - a) * (x + 1) / 2, w * (b - a) / 2


def f_dr(n):
    """F_dr(n) = 2∫₀¹ F(μ, n) μ dμ; for n < 1 split at the critical cosine √(1 − n²)."""
    breaks = [0.0, 1.0] if n >= 1 else [0.0, np.sqrt(1 - n * n), 1.0]
    total = 0.0
    for a, b in zip(breaks, breaks[1:]):
        mu, w = gauss_legendre(400, a, b)
        total += 2 * np.sum(w * fresnel(mu, n) * mu)
    return total


def wolff(n, rho, normalization):
    """K · T(θi) · T(θo), T = 1 − F(θ, n), with the three K of docs/models.md."""
    f0 = fresnel(1.0, n)
    if normalization == "raw":
        k = rho / PI
    elif normalization == "normal":
        k = rho / (PI * (1 - f0) * (1 - f_dr(n)))
    elif normalization == "physical":
        k = rho / (PI * n * n * (1 - rho * f_dr(1 / n)))
    else:
        raise ValueError(normalization)

    def f(ti, to, dphi):
        mi, mo, *_ = directions(ti, to, dphi)
        return k * (1 - fresnel(mi, n)) * (1 - fresnel(mo, n))

    return f


def smith_lambda(theta, m):
    """Λ(θ) = ½ [√(2/π) e^(−a²/2)/a − erfc(a/√2)], a = cot θ / m; Λ(0) = 0."""
    theta = np.asarray(theta, dtype=np.float64)
    with np.errstate(divide="ignore"):
        a = np.cos(theta) / np.sin(theta) / m
    erfc_v = np.vectorize(erfc)(a / np.sqrt(2))
    with np.errstate(divide="ignore", invalid="ignore"):
        lam = 0.5 * (np.sqrt(2 / PI) * np.exp(-a * a / 2) / a - erfc_v)
    return np.where(theta == 0, 0.0, lam)


def ginneken_visibility(ti, to, dphi, m, shadowing):
    lam_max, lam_min = smith_lambda(np.maximum(ti, to), m), smith_lambda(np.minimum(ti, to), m)
    if shadowing == "height_correlated":
        return 1 / (1 + lam_max + lam_min)
    phi = np.abs(np.mod(dphi + PI, 2 * PI) - PI)  # |Δφ| folded into [0, π]
    alpha = 4.41 * phi / (4.41 * phi + 1)
    return 1 / (1 + lam_max + alpha * lam_min)


def slope_integral(mi, mo, wix, wox, woy, m, cells):
    """I on the midpoint grid of [−7m, 7m]² with cells² cells; direction arrays of shape (k,)."""
    h = 14 * m / cells
    p = -7 * m + (np.arange(cells) + 0.5) * h
    p, q = np.meshgrid(p, p, indexing="ij")
    p, q = p.ravel(), q.ravel()
    weight = np.exp(-(p * p + q * q) / (2 * m * m)) / (2 * PI * m * m) / np.sqrt(1 + p * p + q * q) * h * h
    fi = np.maximum(mi[:, None] - p[None, :] * wix[:, None], 0.0)  # wi.y = 0
    fo = np.maximum(mo[:, None] - p[None, :] * wox[:, None] - q[None, :] * woy[:, None], 0.0)
    return (fi * fo) @ weight


def ginneken(m, rho, shadowing="vginneken", cells=800):
    def f(ti, to, dphi):
        ti, to, dphi = (np.ravel(x) for x in np.broadcast_arrays(ti, to, dphi))
        mi, mo, si, so = np.cos(ti), np.cos(to), np.sin(ti), np.sin(to)
        out = np.empty(ti.shape)
        chunk = max(1, 4_000_000 // (cells * cells))
        for k in range(0, ti.size, chunk):
            sl = slice(k, k + chunk)
            integral = slope_integral(
                mi[sl], mo[sl], si[sl], so[sl] * np.cos(dphi[sl]), so[sl] * np.sin(dphi[sl]), m, cells
            )
            vis = ginneken_visibility(ti[sl], to[sl], dphi[sl], m, shadowing)
            out[sl] = rho / PI * vis * integral / (mi[sl] * mo[sl])
        return out

    return f


# ---------------------------------------------------------------------------------------------
# Directional albedo E(θi) = ∫ f cos θo dωo, by the quadrature docs/models.md states.


def albedo(f, theta_i, n_mu=96, n_phi=192, phi_span=2 * PI):
    """Gauss–Legendre in μo on [0, 1] × n_phi azimuth midpoints on [0, phi_span); every model
    here is even in Δφ, so [0, π) counted twice is the whole circle."""
    mu, w_mu = gauss_legendre(n_mu, 0.0, 1.0)
    phi = (np.arange(n_phi) + 0.5) * (phi_span / n_phi)
    to, dphi = np.meshgrid(np.arccos(mu), phi, indexing="ij")
    values = f(np.full(to.shape, theta_i), to, dphi).reshape(to.shape)
    return float(np.sum(values * mu[:, None] * w_mu[:, None]) * (phi_span / n_phi) * (2 * PI / phi_span))


def vg_albedo(m, shadowing, theta_i):
    return albedo(ginneken(m, 1.0, shadowing, cells=160), theta_i, n_mu=32, n_phi=48, phi_span=PI)


# ---------------------------------------------------------------------------------------------
# The tables.

COLUMNS = [
    (0, 0, 0),
    (30, 30, 0),
    (60, 60, 0),
    (60, 60, 180),
    (45, 45, 90),
    (75, 75, 0),
    (75, 75, 180),
    (80, 10, 0),
    (10, 80, 0),
    (60, 20, 180),
]
RHO1 = 0.8
TABLE1 = [
    ("Lambert", lambert(RHO1)),
    ("QON s=0.3", qon(0.3, RHO1)),
    ("QON s=0.5", qon(0.5, RHO1)),
    ("fullON s=0.5", full_on(0.5, RHO1)),
    ("FON r=0.5", fon(0.5, RHO1)),
    ("EON r=0.5", eon(0.5, RHO1)),
    ("EON r=1", eon(1.0, RHO1)),
    ("Wolff raw", wolff(1.5, RHO1, "raw")),
    ("Wolff phys", wolff(1.5, RHO1, "physical")),
    ("vG m=0.3", ginneken(0.3, RHO1)),
    ("vG m=0.5", ginneken(0.5, RHO1)),
]

ANGLES = [0, 30, 60, 80, 89]
TABLE2 = [
    ("Lambert", lambert(1.0)),
    ("QON s=0.25", qon(0.25, 1.0)),
    ("QON s=0.5", qon(0.5, 1.0)),
    ("QON s=1.0", qon(1.0, 1.0)),
    ("fullON s=0.5 (without the ρ² term)", full_on(0.5, 1.0, second_bounce=False)),
    ("fullON s=0.5", full_on(0.5, 1.0)),
    ("fullON s=1.0", full_on(1.0, 1.0)),
    ("FON r=1", fon(1.0, 1.0)),
    ("EON r=1 (exact E_F)", eon(1.0, 1.0)),
    ("Wolff raw", wolff(1.5, 1.0, "raw")),
    ("Wolff normal", wolff(1.5, 1.0, "normal")),
    ("Wolff physical", wolff(1.5, 1.0, "physical")),
]
TABLE2_VG = [
    ("vG m=0.3", 0.3, "vginneken"),
    ("vG m=0.3, `height_correlated`", 0.3, "height_correlated"),
    ("vG m=0.5", 0.5, "vginneken"),
    ("vG m=0.5, `height_correlated`", 0.5, "height_correlated"),
]
TABLE3 = [("0.10", 0.1), ("0.25", 0.25), ("0.50", 0.5), ("0.75", 0.75), ("1.00", 1.0), ("π/2", PI / 2)]


def compute():
    """{table: {row label: [values]}} (None for a cell the table leaves out)."""
    rad = np.radians
    t1 = {}
    ti, to, dphi = (np.array([rad(c[k]) for c in COLUMNS]) for k in range(3))
    for label, f in TABLE1:
        t1[label] = [float(v) for v in f(ti, to, dphi)]
    t2 = {label: [albedo(f, rad(a)) for a in ANGLES] for label, f in TABLE2}
    for label, m, shadowing in TABLE2_VG:
        t2[label] = [vg_albedo(m, shadowing, rad(a)) for a in ANGLES[:-1]] + [None]
    t3 = {}
    for label, sigma in TABLE3:
        s2 = sigma * sigma
        a, b = 1 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09)
        f = qon(sigma, 1.0)
        t3[label] = [a, b, albedo(f, 0.0), albedo(f, rad(89.9))]
    return {"Table 1": t1, "Table 2": t2, "Table 3": t3}


HEADERS = {
    "Table 1": ["model"] + ["/".join(str(x) for x in c) for c in COLUMNS],
    "Table 2": ["model"] + [f"{a}°" for a in ANGLES],
    "Table 3": ["σ (rad)", "A", "B", "E(0°)", "E(89.9°) ≈ A + B/2"],
}
DIGITS = {"Table 1": 5, "Table 2": 4, "Table 3": 4}


def markdown(tables):
    out = []
    for name, rows in tables.items():
        header = HEADERS[name]
        out += [f"### {name}", "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
        for label, values in rows.items():
            cells = ["–" if v is None else f"{v:.{DIGITS[name]}f}" for v in values]
            out.append("| " + " | ".join([label] + cells) + " |")
        out.append("")
    return "\n".join(out)


# ---------------------------------------------------------------------------------------------
# --check: docs/models.md's tables and tests/kernels/reference_tables.rs's arrays.


def doc_tables():
    """{table: {row label: [cell strings]}} from docs/models.md."""
    tables, current = {}, None
    for line in DOC.read_text().splitlines():
        heading = re.match(r"### (Table \d)", line)
        if heading:
            current = tables.setdefault(heading.group(1), {})
        elif line.startswith("## "):
            current = None
        elif current is not None and line.startswith("|") and not line.startswith("|---"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if cells[0] in ("model", "σ (rad)"):
                continue
            current[cells[0]] = cells[1:]
    return tables


# Row labels of the test that differ from the doc's.
TEST_LABELS = {"vG m=0.3 hc": "vG m=0.3, `height_correlated`", "vG m=0.5 hc": "vG m=0.5, `height_correlated`"}


def test_rows():
    """[(table, label, [cell strings])] from the arrays in tests/kernels/reference_tables.rs."""
    text = TEST.read_text()
    t1_start, t2_start = text.index("fn table1()"), text.index("fn table2_white_furnace_albedo()")
    rows = []
    pattern = re.compile(r'\(\s*"([^"]+)",\s*model\(.*?\),\s*\[([^\]]*)\]', re.S)
    for match in pattern.finditer(text):
        table = "Table 1" if t1_start < match.start() < t2_start else "Table 2"
        label = TEST_LABELS.get(match.group(1), match.group(1))
        body = match.group(2)
        repeat = re.fullmatch(r"\s*([0-9.]+);\s*(\d+)\s*", body)
        cells = (
            [repeat.group(1)] * int(repeat.group(2)) if repeat else [c.strip() for c in body.split(",") if c.strip()]
        )
        rows.append((table, label, cells))
    qon_a = re.search(r"for \(sigma, a\) in \[(.*?)\]\s*\{", text, re.S)
    for sigma, a in re.findall(r"\(([^,()]+), ([0-9.]+)\)", qon_a.group(1)):
        label = {"0.1": "0.10", "0.5": "0.50", "1.0": "1.00", "std::f64::consts::FRAC_PI_2": "π/2"}[sigma.strip()]
        rows.append(("Table 3", label, [a, None, None, None]))
    return rows


def same_at_printed_digits(cell, value):
    if cell is None or cell in ("–", "-"):
        return True
    if value is None:
        return False
    decimals = len(cell.split(".")[1]) if "." in cell else 0
    return f"{value:.{decimals}f}" == f"{float(cell):.{decimals}f}"


def label_in_table2(table, label):
    """The test's short names of two Table 2 rows."""
    if table != "Table 2":
        return label
    return {"Wolff phys": "Wolff physical", "EON r=1": "EON r=1 (exact E_F)"}.get(label, label)


def check(tables):
    bad, compared = [], 0
    sources = [("docs/models.md", t, label, cells) for t, rows in doc_tables().items() for label, cells in rows.items()]
    sources += [("reference_tables.rs", t, label, cells) for t, label, cells in test_rows()]
    for source, table, label, cells in sources:
        label = label_in_table2(table, label)
        ours = tables[table].get(label)
        if ours is None:
            bad.append(f"{source} {table} row {label!r}: not computed by this script")
            continue
        if len(cells) < len(ours) and all(v is None for v in ours[len(cells) :]):
            cells = cells + [None] * (len(ours) - len(cells))  # the test leaves out vG's 89° column
        if len(cells) != len(ours):
            bad.append(f"{source} {table} row {label!r}: {len(cells)} cells, expected {len(ours)}")
            continue
        for k, (cell, value) in enumerate(zip(cells, ours)):
            if cell is None:
                continue
            compared += 1
            if not same_at_printed_digits(cell, value):
                col = HEADERS[table][k + 1]
                bad.append(f"{source} {table} {label!r} at {col}: holds {cell}, computed {value:.7f}")
    for line in bad:
        print("MISMATCH", line)
    print(f"{compared} cells compared, {len(bad)} mismatches")
    return not bad


def text_values(tables):
    """Numbers quoted in docs/models.md's text: (what, as printed there, computed)."""
    n = 1.5
    s2 = np.linspace(0.01, 1.0, 9901) ** 2
    grazing = 1 - 0.5 * s2 / (s2 + 0.33) + 0.5 * 0.45 * s2 / (s2 + 0.09)  # QON's E(90°) = A + B/2
    t2 = tables["Table 2"]
    vg_alpha = [4.41 * phi / (4.41 * phi + 1) for phi in (PI / 2, PI)]
    return [
        ("Fresnel F(0) at n = 1.5", "0.0400", float(fresnel(1.0, n))),
        ("F_dr,ext(1.5)", "0.09178", f_dr(n)),
        ("F_dr,int = F_dr(1/1.5)", "0.59635", f_dr(1 / n)),
        ("1 − F_dr,int − (1 − F_dr,ext)/n² (the identity)", "0.00000", (1 - f_dr(1 / n)) - (1 - f_dr(n)) / n**2),
        ("Wolff physical E(0°), n = 1.5, ρ = 1", "0.960", t2["Wolff physical"][0]),
        ("Wolff normal E(0°)", "1.000", t2["Wolff normal"][0]),
        ("Wolff raw E(0°)", "0.872", t2["Wolff raw"][0]),
        ("Wolff physical E(0°) at ρ = 0.8", "0.593", albedo(wolff(n, 0.8, "physical"), 0.0)),
        ("Wolff physical E(89°), ρ = 1", "0.10", t2["Wolff physical"][4]),
        ("QON: max over σ of A + B/2", "1.0152", float(grazing.max())),
        ("QON: σ of that maximum", "0.20", float(np.sqrt(s2[grazing.argmax()]))),
        ("QON: A + B/2 > 1 for σ below", "0.326", float(np.sqrt(s2[np.nonzero(grazing > 1)[0].max()]))),
        ("fullON σ = 0.5 E(89°)", "1.0166", t2["fullON s=0.5"][4]),
        ("vG m = 0.3 E", "0.926", t2["vG m=0.3"][0]),
        ("vG m = 0.5 E", "0.836", t2["vG m=0.5"][0]),
        ("vG α(π/2)", "0.874", vg_alpha[0]),
        ("vG α(π)", "0.933", vg_alpha[1]),
        ('fullON σ = 0.5 at 75/75/180 ("0.117 vs 0.038")', "0.117", tables["Table 1"]["fullON s=0.5"][6]),
        ("vG m = 0.5 at 75/75/180", "0.038", tables["Table 1"]["vG m=0.5"][6]),
    ]


def check_text(tables):
    doc = DOC.read_text()
    bad = 0
    for what, printed, value in text_values(tables):
        in_doc = printed in doc or what.startswith("1 − F_dr,int")
        ok = in_doc and same_at_printed_digits(printed, value)
        bad += not ok
        print(
            f"{'OK      ' if ok else 'MISMATCH'} {what}: docs/models.md {printed}{'' if in_doc else ' (not found in the doc)'},"
            f" computed {value:.6f}"
        )
    return bad == 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--check", action="store_true", help="compare with docs/models.md and the test's arrays")
    args = parser.parse_args()
    tables = compute()
    if args.check:
        tables_ok = check(tables)
        text_ok = check_text(tables)
        sys.exit(0 if tables_ok and text_ok else 1)
    print(markdown(tables))


if __name__ == "__main__":
    main()
