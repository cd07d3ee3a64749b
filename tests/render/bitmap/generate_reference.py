#!/usr/bin/env python3
"""Prints what Mitsuba 3.9.1's `bitmap` texture (scalar_rgb) gives for the inline oracles of
tests/render/bitmap.rs and checks them against the numbers the test holds. Run by hand with the
venv's Python from the repository root (under 1 s):

    .venv/bin/python tests/render/bitmap/generate_reference.py

The same tiny images as the test's are written (8-bit PNG through `mi.Bitmap`, linear float32
EXR for the test's `from_linear` textures) and looked up with `texture.eval(si)` at the test's
uv. Covered (test function → values):

* `eight_bit_texels_are_srgb_decoded`: grey 128 → 0.215861 (bilinear and nearest, any uv);
  `raw` → 128/255.
* `bilinear_mixes_linear_values`: red, green / blue, grey 128 at the centre and `mean()` →
  0.303965; black | white columns at u = 0.5 and 0.375 → 0.5 and 0.25.
* `v_zero_is_the_top_row`: red top row, blue bottom row.
* `wrap_modes_pick_the_expected_texels`, `to_uv_is_applied_first`: the 4×2 column texture
  (hand-derived in the test) under repeat / mirror / clamp and `to_uv`.
* `alpha_is_dropped_and_gray_is_replicated`: RGBA (200, 100, 50, 128) → (0.577581, 0.127438,
  0.031896) and `mean()` 0.216275 (the luminance; matte's `mean_luminance`); grey + alpha
  (200, 128) → 0.577581; a 1-channel image.
* `tiny_images_are_padded_and_jpeg_is_srgb`: a 1×1 grey and a 1×2 red / blue image.

Prints one line per check and exits 1 if any differs.
"""

import sys
import tempfile
from pathlib import Path

import mitsuba as mi
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "common"))
from reference_check import check, finish  # noqa: E402

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)
TMP = Path(tempfile.mkdtemp(prefix="matte-bitmap-ref-"))


def image(name, texels, dtype=np.uint8):
    """texels: rows (top first) of pixels."""
    path = TMP / name
    mi.Bitmap(np.asarray(texels, dtype=dtype)).write(str(path))
    return str(path)


def texture(path, **props):
    return mi.load_dict({"type": "bitmap", "filename": path, **props})


def ev(t, u, v):
    si = mi.SurfaceInteraction3f()
    si.uv = [u, v]
    return [float(c) for c in t.eval(si)]


RED, GREEN, BLUE, GRAY = [255, 0, 0], [0, 255, 0], [0, 0, 255], [128, 128, 128]
X, Y, Z = [1, 0, 0], [0, 1, 0], [0, 0, 1]

# eight_bit_texels_are_srgb_decoded
gray = image("gray.png", [[GRAY, GRAY], [GRAY, GRAY]])
for filt in ("bilinear", "nearest"):
    t = texture(gray, filter_type=filt)
    for uv in [(0.3, 0.7), (-5.2, 3.9), (0.0, 0.0)]:
        check(f"grey 128, {filt}, uv {uv}", ev(t, *uv), [0.215861] * 3, 2e-6)
check("grey 128, raw", ev(texture(gray, raw=True), 0.5, 0.5), [128 / 255] * 3, 1e-7)

# bilinear_mixes_linear_values
t = texture(image("mix.png", [[RED, GREEN], [BLUE, GRAY]]))
check("red green / blue grey at the centre", ev(t, 0.5, 0.5), [0.303965] * 3, 2e-6)
check("red green / blue grey mean()", t.mean(), 0.303965, 2e-6)
t = texture(image("bw.png", [[[0] * 3, [255] * 3], [[0] * 3, [255] * 3]]))
check("black | white at u = 0.5", ev(t, 0.5, 0.3), [0.5] * 3, 1e-6)
check("black | white at u = 0.375", ev(t, 0.375, 0.3), [0.25] * 3, 1e-6)

# v_zero_is_the_top_row
rb = image("rb.png", [[RED, RED], [BLUE, BLUE]])
for filt in ("bilinear", "nearest"):
    t = texture(rb, filter_type=filt)
    check(f"red top / blue bottom, {filt}, (0.25, 0.25)", ev(t, 0.25, 0.25), X, 1e-6)
    check(f"red top / blue bottom, {filt}, (0.75, 0.75)", ev(t, 0.75, 0.75), Z, 1e-6)
t = texture(rb, filter_type="nearest")
check("red top / blue bottom, nearest, (0.9, 0.49)", ev(t, 0.9, 0.49), X)
check("red top / blue bottom, nearest, (0.1, 0.5)", ev(t, 0.1, 0.5), Z)

# wrap_modes_pick_the_expected_texels: 4×2 texels, x = 0.1·(column + 1), y = row.
columns = image("columns.exr", [[[0.1 * (c + 1), r, 0.0] for c in range(4)] for r in range(2)], np.float32)
CASES = [(-0.1, [3, 0, 0]), (1.1, [0, 3, 3]), (-1.1, [3, 3, 0]), (2.3, [1, 1, 3]), (1.9, [3, 0, 3]), (0.6, [2, 2, 2])]
for k, wrap in enumerate(["repeat", "mirror", "clamp"]):
    t = texture(columns, filter_type="nearest", wrap_mode=wrap)
    for u, want in CASES:
        check(f"columns, nearest, {wrap}, u = {u}", ev(t, u, 0.25)[0], 0.1 * (want[k] + 1), 1e-7)
    check(f"columns, nearest, {wrap}, v = -0.25 (row)", ev(t, 0.1, -0.25)[1], [1.0, 0.0, 0.0][k])
for wrap, want in [("repeat", 0.75 * 0.1 + 0.25 * 0.4), ("clamp", 0.1), ("mirror", 0.1)]:
    check(f"columns, bilinear, {wrap}, u = 1/16", ev(texture(columns, wrap_mode=wrap), 1 / 16, 0.25)[0], want, 1e-6)

# to_uv_is_applied_first
t = texture(columns, filter_type="nearest", to_uv=mi.ScalarTransform4f().scale([2, 2, 1]))
check("columns, to_uv scale 2, (0.6, 0.1)", ev(t, 0.6, 0.1)[0], 0.1, 1e-7)
t = texture(columns, filter_type="nearest", wrap_mode="clamp", to_uv=mi.ScalarTransform4f().translate([0.25, 0, 0]))
check("columns, to_uv translate 0.25, clamp, (0.1, 0.1)", ev(t, 0.1, 0.1)[0], 0.2, 1e-7)

# alpha_is_dropped_and_gray_is_replicated
t = texture(image("rgba.png", [[[200, 100, 50, 128]] * 2] * 2))
check("RGBA (200, 100, 50, 128)", ev(t, 0.3, 0.6), [0.577581, 0.127438, 0.031896], 2e-6)
check("RGBA mean() (luminance)", t.mean(), 0.216275, 2e-6)
check("grey + alpha (200, 128)", ev(texture(image("ya.png", [[[200, 128]] * 2] * 2)), 0.3, 0.6), [0.577581] * 3, 2e-6)
t = texture(image("y.png", [[[0], [255]], [[255], [0]]]), filter_type="nearest")
check("1-channel 0 255 / 255 0, nearest, (0.75, 0.25)", ev(t, 0.75, 0.25), [1.0] * 3)

# tiny_images_are_padded_and_jpeg_is_srgb
check("1×1 grey 128 at (0.9, 0.1)", ev(texture(image("one.png", [[GRAY]])), 0.9, 0.1), [0.215861] * 3, 2e-6)
t = texture(image("tall.png", [[RED], [BLUE]]), filter_type="nearest")
check("1×2 red / blue, nearest, (0.9, 0.9)", ev(t, 0.9, 0.9), Z)

finish()
