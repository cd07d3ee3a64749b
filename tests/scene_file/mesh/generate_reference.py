#!/usr/bin/env python3
"""Prints what Mitsuba 3.9.1 (scalar_rgb) gives for the inline oracles of tests/scene_file/mesh.rs
and checks them against the numbers the test holds. Run by hand with the venv's Python from
the repository root (about 1 s):

    .venv/bin/python tests/scene_file/mesh/generate_reference.py

Covered (test function → what Mitsuba is asked):

* `obj_smooth_normals_match_mitsuba_cube_corner`: the 8-vertex OBJ cube `CUBE8` without `vn`,
  `scene.ray_intersect` straight down at (0.9, 0.9): `si.sh_frame.n`; its `vertex_normals`.
* `degenerate_triangles_are_kept_without_nan_normals`: `vertex_normals` of the OBJ with a
  zero-area triangle (vertex 2 only touches it: Mitsuba's placeholder (1, 0, 0)).
* `mitsuba_cube()` / `cube_matches_mitsuba_buffers`: `mi.traverse(mi.load_dict({'type':
  'cube'}))` buffers, with and without `face_normals`, parsed from the test's literal and compared
  exactly; `surface_area()`.
* `cube_under_a_mirroring_transform_matches_mitsuba`: the cube under scale(−1, 2, 1).
* `rectangle_matches_mitsuba_ray_queries`: rays down −z onto the default rectangle and onto
  scale(−1, 2, 1): `si.uv`, `si.prim_index`, `si.n`, `si.sh_frame.n`; `surface_area()`.

The OBJ with only zero-area triangles in the same test has no Mitsuba oracle: Mitsuba refuses it
("DiscreteDistribution: no probability mass found!"); the test only asks matte for unit normals.
Prints one line per check and exits 1 if any differs.
"""

import re
import sys
import tempfile
from pathlib import Path

import mitsuba as mi
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "common"))
from functools import partial  # noqa: E402

from reference_check import check as _check  # noqa: E402
from reference_check import finish

check = partial(_check, threshold=12)

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)

ROOT = Path(__file__).resolve().parents[3]
TEST = ROOT / "tests" / "scene_file" / "mesh.rs"
TMP = Path(tempfile.mkdtemp(prefix="matte-mesh-ref-"))


def obj(name, text):
    path = TMP / name
    path.write_text(text)
    return str(path)


def buffers(shape):
    p = mi.traverse(shape)
    return {k: np.array(p[k]) for k in ("vertex_positions", "vertex_normals", "vertex_texcoords", "faces")}


def down(scene, x, y):
    return scene.ray_intersect(mi.Ray3f([x, y, 5.0], [0.0, 0.0, -1.0]))


# The test's literal of `fn mitsuba_cube()`, parsed.
def test_cube():
    text = TEST.read_text()
    body = text[text.index("fn mitsuba_cube()") : text.index("fn cube_matches_mitsuba_buffers()")]
    num = r"(-?[0-9.]+)"
    pos_block = body[body.index("let pos") : body.index("let nrm")]
    nrm_block = body[body.index("let nrm") : body.index("let uv")]
    uv_block = body[body.index("let uv") : body.index("let faces")]
    faces_block = body[body.index("let faces") :]
    triple = re.compile(rf"\[{num}, {num}, {num}\]")
    pos = [[float(a) for a in m] for m in triple.findall(pos_block)]
    nrm = [[float(a) for a in m] for m in triple.findall(nrm_block) for _ in range(4)]
    uv = [[float(a) for a in m] for m in re.findall(rf"\[{num}, {num}\]", uv_block)] * 6
    faces = [[int(a) for a in m] for m in triple.findall(faces_block)]
    return np.array(pos).ravel(), np.array(nrm).ravel(), np.array(uv).ravel(), np.array(faces).ravel()


CUBE8 = (
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
)

# obj_smooth_normals_match_mitsuba_cube_corner
scene = mi.load_dict({"type": "scene", "s": {"type": "obj", "filename": obj("cube8.obj", CUBE8)}})
check("CUBE8 shading normal at (0.9, 0.9, 1)", down(scene, 0.9, 0.9).sh_frame.n, [0.556, 0.556, 0.618], 1e-3)
b = buffers(scene.shapes()[0])
positions = b["vertex_positions"].reshape(-1, 3)
check(
    "CUBE8 vertex normals = corner directions",
    b["vertex_normals"].reshape(-1, 3),
    positions / np.linalg.norm(positions, axis=1, keepdims=True),
    1e-6,
)

# degenerate_triangles_are_kept_without_nan_normals
n = buffers(
    mi.load_dict({"type": "obj", "filename": obj("deg.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n")})
)
n = n["vertex_normals"].reshape(-1, 3)
check("degenerate OBJ: normal of vertex 0", n[0], [0, 0, 1], 1e-6)
check("degenerate OBJ: placeholder normal of vertex 2", n[2], [1, 0, 0])

# mitsuba_cube(), cube_matches_mitsuba_buffers
pos, nrm, uv, faces = test_cube()
for face_normals in (False, True):
    cube = mi.load_dict({"type": "cube", "face_normals": face_normals})
    b = buffers(cube)
    check(f"cube face_normals={face_normals}: vertex_positions", b["vertex_positions"], pos)
    check(f"cube face_normals={face_normals}: vertex_normals", b["vertex_normals"], nrm)
    check(f"cube face_normals={face_normals}: vertex_texcoords", b["vertex_texcoords"], uv)
    check(f"cube face_normals={face_normals}: faces", b["faces"], faces)
check("cube surface_area", mi.load_dict({"type": "cube"}).surface_area(), 24.0)

# cube_under_a_mirroring_transform_matches_mitsuba
mirror = mi.ScalarTransform4f().scale([-1, 2, 1])
cube = mi.load_dict({"type": "cube", "to_world": mirror})
b = buffers(cube)
check(
    "mirrored cube: vertex_positions = (-x, 2y, z)",
    b["vertex_positions"].reshape(-1, 3),
    pos.reshape(-1, 3) * [-1, 2, 1],
)
expect = np.repeat([[0, -1, 0], [0, 1, 0], [-1, 0, 0], [0, 0, 1], [1, 0, 0], [0, 0, -1]], 4, axis=0)
check("mirrored cube: vertex_normals (+x and -x faces swapped)", b["vertex_normals"].reshape(-1, 3), expect, 1e-6)
check("mirrored cube: surface_area", cube.surface_area(), 2.0 * (2.0 * 4.0 + 2.0 * 4.0 + 2.0 * 2.0))

# rectangle_matches_mitsuba_ray_queries
for to_world, cases, area in [
    (None, [((0.5, -0.5), (0.75, 0.25), 0, -1), ((-0.6, 0.2), (0.2, 0.6), 0, -1)], 4.0),
    (mirror, [((0.5, -0.5), (0.25, 0.375), 0, 1), ((-0.6, 0.2), (0.8, 0.55), 1, 1)], 8.0),
]:
    shape = {"type": "rectangle"} if to_world is None else {"type": "rectangle", "to_world": to_world}
    scene = mi.load_dict({"type": "scene", "s": shape})
    name = "rectangle" if to_world is None else "rectangle scale(-1,2,1)"
    for (x, y), uv_want, prim, flipped in cases:
        si = down(scene, x, y)
        check(f"{name} at ({x}, {y}): uv", si.uv, uv_want, 1e-6)
        check(f"{name} at ({x}, {y}): n", si.n, [0, 0, -1] if flipped == 1 else [0, 0, 1], 1e-6)
        check(f"{name} at ({x}, {y}): sh_frame.n", si.sh_frame.n, [0, 0, 1], 1e-6)
        if to_world is not None:  # the test checks the triangle index only under the mirror
            check(f"{name} at ({x}, {y}): prim_index", si.prim_index, prim)
    check(f"{name}: surface_area", scene.shapes()[0].surface_area(), area)

finish()
