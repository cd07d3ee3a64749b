#!/usr/bin/env python3
"""Prints what Mitsuba 3.9.1's `volume` texture (scalar_rgb) gives for the table `MITSUBA` of
tests/render/volume_texture.rs and checks the numbers the test holds. Run by hand with the
venv's Python from the repository root (under 1 s):

    .venv/bin/python tests/render/volume_texture/generate_reference.py [--print]

It writes the test's two grids with its own `.vol` writer (the format of Mitsuba's
`VolumeGrid::read`, `src/render/volumegrid.cpp`) from the same formulas as the test
(`grid3.vol`: 4×3×2 voxels, RGB; `grid1.vol`: 3×2×2 voxels, one channel; both with the bounding
box (−1, 0, 2)–(3, 1.5, 4)), loads each row's `<volume>` inside a `<texture type="volume">`,
and evaluates `eval` and `eval_1` at the row's world-space point (`si.p`; the uv is (0, 0)).
The rows cover trilinear and nearest filtering, the clamp, repeat and mirror wrap modes,
`to_world`, `use_grid_bbox`, a one-channel grid, `raw`/`accel`/`max_value` (no effect in RGB),
and `constvolume` with a colour, a float and a checkerboard value. `--print` prints the rows
in Rust syntax. It also checks the refusals `property_and_placement_errors` mirrors: a number
as `volume` ("wrong type (expected object, got float)"), and a volume texture where Mitsuba
asks for `mean()` (a `plastic`'s `diffuse_reflectance`, an `oren_nayar` `sigma` through
matte's plugin: "Texture::mean(): not implemented!"). Prints one line per check and exits 1 if
any differs.
"""

import re
import struct
import sys
import tempfile
from pathlib import Path

import matte_mitsuba  # noqa: F401 (registers matte's BSDFs: oren_nayar)
import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "common"))
from reference_check import check, check_true, finish  # noqa: E402

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)
TEST = Path(__file__).resolve().parents[1] / "volume_texture.rs"
TMP = Path(tempfile.mkdtemp(prefix="matte-volume-ref-"))
BBOX = (-1.0, 0.0, 2.0, 3.0, 1.5, 4.0)


def grid3(x, y, z, c):
    return 0.05 + 0.1 * x + 0.2 * y + 0.35 * z + 0.03 * c + 0.05 * ((x * y + z) % 3)


def grid1(x, y, z):
    return 0.1 + 0.15 * x + 0.25 * y * y + 0.3 * z


def write_vol(path, res, channels, value):
    xres, yres, zres = res
    data = [value(x, y, z, c) for z in range(zres) for y in range(yres) for x in range(xres) for c in range(channels)]
    head = b"VOL" + bytes([3]) + struct.pack("<iiiii", 1, xres, yres, zres, channels) + struct.pack("<6f", *BBOX)
    path.write_bytes(head + struct.pack(f"<{len(data)}f", *data))


write_vol(TMP / "grid3.vol", (4, 3, 2), 3, grid3)
write_vol(TMP / "grid1.vol", (3, 2, 2), 1, lambda x, y, z, c: grid1(x, y, z))

ROW = re.compile(r'\(\s*r#"(.*?)"#,\s*\[([^\]]*)\],\s*\[([^\]]*)\],\s*([-+\d.eE]+),?\s*\)', re.S)
text = TEST.read_text()
table = text[text.index("const MITSUBA") :]
table = table[: table.index("];")]
rows = ROW.findall(table)
if not rows:
    sys.exit(f"no rows found in {TEST}")

printed = []
for xml, point, want_eval, want_eval_1 in rows:
    p = [float(v) for v in point.split(",")]
    local = xml.replace('value="grid', f'value="{TMP}/grid')
    tex = mi.load_string(f'<texture version="3.0.0" type="volume">{local}</texture>')
    si = mi.SurfaceInteraction3f()
    si.p = p
    si.uv = [0, 0]
    got = [float(c) for c in tex.eval(si)]
    got_1 = float(tex.eval_1(si))
    label = f"{xml[:90]} at {p}"
    check(f"eval {label}", got, [float(v) for v in want_eval.split(",")], 2e-6)
    check(f"eval_1 {label}", got_1, float(want_eval_1), 2e-6)
    printed.append(
        f'    (r#"{xml}"#, [{", ".join(v.strip() for v in point.split(","))}], '
        f"[{', '.join(f'{v:.7}' for v in got)}], {got_1:.7}),"
    )


def refusal(xml):
    try:
        mi.load_string(xml)
    except Exception as e:  # noqa: BLE001 (Mitsuba raises RuntimeError)
        return str(e)
    return "loaded"


CONST = '<texture type="volume" name="NAME"><volume type="constvolume" name="volume"/></texture>'
msg = refusal('<texture version="3.0.0" type="volume"><float name="volume" value="0.5"/></texture>')
check_true("a float as volume", "wrong type (expected object, got float)" in msg, msg[-120:])
for bsdf, name in [("plastic", "diffuse_reflectance"), ("oren_nayar", "sigma")]:
    msg = refusal(f'<bsdf version="3.0.0" type="{bsdf}">{CONST.replace("NAME", name)}</bsdf>')
    check_true(f"{bsdf} {name} as a volume texture", "Texture::mean(): not implemented!" in msg, msg[-120:])
msg = refusal(f'<bsdf version="3.0.0" type="oren_nayar">{CONST.replace("NAME", "reflectance")}</bsdf>')
check_true("oren_nayar reflectance as a volume texture loads", msg == "loaded", msg[-120:])
if "--print" in sys.argv:
    print("\n".join(printed))
finish()
