#!/usr/bin/env python3
"""Prints what Mitsuba 3.9.1's XML parser (scalar_rgb) gives for the inline transform and colour
oracles of tests/scene_file/xml.rs and checks them against the numbers the test holds. Run by
hand with the venv's Python from the repository root (under 1 s):

    .venv/bin/python tests/scene_file/xml/generate_reference.py

Transforms: each `<transform name="to_world">` body of the test, inside a `rectangle`, through
`mi.parser.parse_string`; the property is Mitsuba's double-precision `AffineTransform4d`,
compared with the test's matrix or mapped point at the test's tolerance
(`first_listed_operation_is_applied_first`,
`rotate_is_right_handed_in_degrees_with_an_unnormalized_axis`,
`matrix_is_row_major_and_defaults_fill_in`, `lookat_columns_are_left_up_dir_origin`).

Colours: each `<spectrum>`/`<rgb>` property of the test read as Mitsuba's plugins read it:
`Properties.get_texture` (bounded, matte's `ColorUse::Bounded`), `get_unbounded_texture`
(`Unbounded`) and `get_emissive_texture` (`Emissive`), evaluated at a default surface interaction
and printed with the float32 digits the test holds (`rgb_float_and_constant_spectrum_per_use`,
`unit_constant_emission_is_the_equal_energy_colour`, `sampled_spectra_match_mitsuba`).

Prints one line per check and exits 1 if any differs.
"""

import math
import sys
from pathlib import Path

import mitsuba as mi
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "common"))
from functools import partial  # noqa: E402

from reference_check import check as _check  # noqa: E402
from reference_check import finish

check = partial(_check, precision=16)

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)
CONFIG = mi.parser.ParserConfig("scalar_rgb")


def props(body, plugin="rectangle", tag="shape"):
    state = mi.parser.parse_string(CONFIG, f'<scene version="3.0.0"><{tag} type="{plugin}">{body}</{tag}></scene>')
    return state.nodes[1].props


def to_world(ops):
    return np.array(props(f'<transform name="to_world">{ops}</transform>')["to_world"].matrix, dtype=np.float64)


def point(m, p):
    return (m @ np.append(p, 1.0))[:3]


def vector(m, v):
    return m[:3, :3] @ np.asarray(v, dtype=np.float64)


# first_listed_operation_is_applied_first
check(
    "translate x=1 then rotate y 90: origin",
    point(to_world('<translate x="1"/><rotate y="1" angle="90"/>'), [0, 0, 0]),
    [0, 0, -1],
    1e-15,
)
check(
    "rotate y 90 then translate x=1: origin",
    point(to_world('<rotate y="1" angle="90"/><translate x="1"/>'), [0, 0, 0]),
    [1, 0, 0],
    1e-15,
)
check(
    "scale 2 then translate (1, 2, 3)",
    to_world('<scale value="2"/><translate value="1 2 3"/>'),
    [[2, 0, 0, 1], [0, 2, 0, 2], [0, 0, 2, 3], [0, 0, 0, 1]],
)

# rotate: right-handed, unnormalised axis
check("rotate x 90: +y", vector(to_world('<rotate x="1" angle="90"/>'), [0, 1, 0]), [0, 0, 1], 1e-15)
check(
    "rotate x=2 90",
    to_world('<rotate x="2" angle="90"/>'),
    [[4, 0, 0, 0], [0, 0, -2, 0], [0, 2, 0, 0], [0, 0, 0, 1]],
    1e-15,
)
s, c = 0.5, math.sqrt(3) / 2
k = 1 - c
check(
    "rotate (1, 1, 0) 30",
    to_world('<rotate value="1, 1, 0" angle="30"/>'),
    [[c + k, k, s, 0], [k, c + k, -s, 0], [-s, s, c, 0], [0, 0, 0, 1]],
    1e-15,
)
check("rotate z 180: +x", vector(to_world('<rotate z="1" angle="180"/>'), [1, 0, 0]), [-1, 0, 0], 1e-15)

# matrix_is_row_major_and_defaults_fill_in
check(
    "matrix 16 values: origin",
    point(to_world('<matrix value="1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1"/>'), [0, 0, 0]),
    [5, 6, 7],
)
check(
    "matrix 9 values",
    to_world('<matrix value="1,2,3,4,5,6,7,8,9"/>'),
    [[1, 2, 3, 0], [4, 5, 6, 0], [7, 8, 9, 0], [0, 0, 0, 1]],
)
check("translate y=2", to_world('<translate y="2"/>'), [[1, 0, 0, 0], [0, 1, 0, 2], [0, 0, 1, 0], [0, 0, 0, 1]])
check("scale z=3", to_world('<scale z="3"/>'), np.diag([1, 1, 3, 1]))
check("scale value 2 3 4", to_world('<scale value="2 3 4"/>'), np.diag([2, 3, 4, 1]))

# lookat_columns_are_left_up_dir_origin
check(
    "lookat (0,0,5) → 0, up +y",
    to_world('<lookat origin="0,0,5" target="0,0,0" up="0,1,0"/>'),
    [[-1, 0, 0, 0], [0, 1, 0, 0], [0, 0, -1, 5], [0, 0, 0, 1]],
)
m = to_world('<lookat origin="1 2 3" target="0 0 0" up="0 0 1"/>')
d = -np.array([1, 2, 3]) / math.sqrt(14)
left = np.cross([0, 0, 1], d)
left /= np.linalg.norm(left)
check(
    "lookat (1,2,3) → 0, up +z: columns left, up', dir", m[:3, :3], np.column_stack([left, np.cross(d, left), d]), 1e-15
)
check(
    "lookat (0,0,0) → (0,0,−1), no up",
    to_world('<lookat origin="0,0,0" target="0 0 -1"/>'),
    [[0, 1, 0, 0], [1, 0, 0, 0], [0, 0, -1, 0], [0, 0, 0, 1]],
    1e-15,
)
check(
    "lookat (0,0,0) → (0,0,1), up 0",
    to_world('<lookat origin="0,0,0" target="0 0 1" up="0 0 0"/>'),
    [[0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]],
    1e-15,
)
check(
    "lookat (1,2,3) → 0, no up",
    to_world('<lookat origin="1,2,3" target="0 0 0"/>'),
    [
        [-0.079286509705, 0.960356745147, -0.267261241912, 1.0],
        [0.84142698059, -0.079286509705, -0.534522483825, 2.0],
        [-0.534522483825, -0.267261241912, -0.801783725737, 3.0],
        [0.0, 0.0, 0.0, 1.0],
    ],
    1e-11,
)

# Colours.
SI = mi.SurfaceInteraction3f()
USES = {"Bounded": "get_texture", "Unbounded": "get_unbounded_texture", "Emissive": "get_emissive_texture"}


def color(p, name, use):
    return [float(v) for v in getattr(p, USES[use])(name).eval(SI)]


# rgb_float_and_constant_spectrum_per_use
p = props(
    '<rgb name="c" value="0.2 0.4 0.6"/><float name="f" value="0.3"/><spectrum name="s" value="2.5"/>'
    '<rgb name="hot" value="-1 2 0.5"/>',
    "diffuse",
    "bsdf",
)
for use in USES:
    check(f"<rgb 0.2 0.4 0.6> {use}", color(p, "c", use), [0.2, 0.4, 0.6], 1e-7)
    check(f"<float 0.3> {use}", color(p, "f", use), [0.3] * 3, 1e-7)
check("<spectrum 2.5> Bounded", color(p, "s", "Bounded"), [2.5] * 3)
check("<spectrum 2.5> Unbounded", color(p, "s", "Unbounded"), [2.5] * 3)
check("<spectrum 2.5> Emissive", color(p, "s", "Emissive"), [3.011985, 2.3707275, 2.27229], 2e-6)
check("<rgb -1 2 0.5> Emissive", color(p, "hot", "Emissive"), [-1.0, 2.0, 0.5])
check("<rgb -1 2 0.5> Unbounded", color(p, "hot", "Unbounded"), [-1.0, 2.0, 0.5])
try:
    color(p, "hot", "Bounded")
    check("<rgb -1 2 0.5> Bounded is an error", False, True)
except Exception as e:  # noqa: BLE001 (Mitsuba raises a plain RuntimeError)
    check(f"<rgb -1 2 0.5> Bounded is an error ({str(e).splitlines()[-1].strip()[:60]})", True, True)

# unit_constant_emission_is_the_equal_energy_colour
p = props('<spectrum name="radiance" value="1"/>', "diffuse", "bsdf")
check(
    "<spectrum 1> Emissive",
    color(p, "radiance", "Emissive"),
    [1.204793930053711, 0.948291003704071, 0.9089160561561584],
    1e-12,
)

# sampled_spectra_match_mitsuba
p = props(
    '<spectrum name="flat" value="360:0.5 830:0.5"/><spectrum name="ramp" value="400:0.2, 500:0.8 600:0.4"/>'
    '<spectrum name="red" value="550:0.1 600:0.9 700:0.9"/><spectrum name="k" value="400:3 700:2"/>'
    '<spectrum name="dip" value="400:1 450:0 700:0"/>',
    "diffuse",
    "bsdf",
)
for name, use, want, tol in [
    ("flat", "Bounded", [0.4994926452636719, 0.4994368553161621, 0.499400794506073], 2e-7),
    ("flat", "Emissive", [0.6024418473243713, 0.4741140902042389, 0.4546334147453308], 2e-7),
    ("ramp", "Bounded", [0.0, 0.6751750707626343, 0.5193376541137695], 2e-7),
    ("ramp", "Unbounded", [0.0, 0.6751750707626343, 0.5193376541137695], 2e-7),
    ("ramp", "Emissive", [0.0, 0.6430652737617493, 0.4639976918697357], 2e-7),
    ("red", "Bounded", [1.0, 0.12008368223905563, 0.0], 2e-7),
    ("k", "Unbounded", [2.181877851486206, 2.5228137969970703, 2.8486852645874023], 1e-6),
    ("dip", "Emissive", [0.02165452018380165, 0.0, 0.15275929868221283], 2e-7),
]:
    check(f"<spectrum {name}> {use}", color(p, name, use), want, tol)

finish()
