#!/usr/bin/env python3
"""Writes the `.serialized` files of tests/scene_file/mesh.rs and what Mitsuba 3.9.1 (scalar_rgb) loads
from them, the oracle. Run by hand with the venv's Python from the repository root:

    .venv/bin/python tests/scene_file/serialized/generate_reference.py

* v4.serialized: version 4, f32, two meshes with normals and uvs (the bundled torus and a
  tilted quad pair), then the bundled twisted box (no normals, vertex colours).
* v3_double.serialized: version 3 (no names, 32-bit dictionary), f64 arrays, three meshes:
  the twisted box, the torus without uvs, a single triangle with normals and uvs.
* mitsuba_reference.json: for each (file, shape_index, face_normals, to_world) case, the
  `vertex_positions`, `vertex_normals`, `vertex_texcoords` and `faces` buffers of
  `mi.traverse(mi.load_dict({"type": "serialized", ...}))`, flattened.
"""

import json
import sys
from pathlib import Path

import mitsuba as mi

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[2] / "mitsuba_scenes" / "assets"))
from make_assets import serialized, torus, twisted_box  # noqa: E402

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)

quads = {
    "positions": [(0, 0, 0), (1, 0, 0.2), (1, 1, 0.4), (0, 1, 0.1), (2, 0, 0), (2, 1, 0.3)],
    "normals": [(0, 0, 1), (0.1, 0, 1), (0, 0.2, 1), (-0.1, 0.1, 1), (0.3, 0, 1), (0, -0.3, 1)],
    "uvs": [(0, 0), (0.5, 0), (0.5, 1), (0, 1), (1, 0), (1, 1)],
    "faces": [(0, 1, 2), (0, 2, 3), (1, 4, 5), (1, 5, 2)],
    "name": "quads",
}
triangle = {
    "positions": [(0, 0, 0), (1, 0, 0), (0, 1, 0)],
    "normals": [(0, 0, 1)] * 3,
    "uvs": [(0, 0), (1, 0), (0, 1)],
    "faces": [(0, 1, 2)],
    "double": True,
}
torus_no_uv = {k: v for k, v in torus(8, 4).items() if k != "uvs"}
boxd = dict(twisted_box(), double=True)

serialized(HERE / "v4.serialized", [torus(), quads, twisted_box()], version=4)
serialized(HERE / "v3_double.serialized", [boxd, dict(torus_no_uv, double=True), triangle], version=3)

TO_WORLD = [[0.0, -2.0, 0.0, 1.0], [1.0, 0.0, 0.0, -0.5], [0.0, 0.0, 0.5, 2.0], [0, 0, 0, 1]]
CASES = [
    ("v4.serialized", 0, False, None),
    ("v4.serialized", 1, False, TO_WORLD),
    ("v4.serialized", 2, False, None),
    ("v4.serialized", 0, True, TO_WORLD),
    ("v3_double.serialized", 0, False, TO_WORLD),
    ("v3_double.serialized", 1, False, None),
    ("v3_double.serialized", 2, False, None),
]

cases = []
for name, index, face_normals, to_world in CASES:
    d = {"type": "serialized", "filename": str(HERE / name), "shape_index": index, "face_normals": face_normals}
    if to_world is not None:
        d["to_world"] = mi.ScalarTransform4f(to_world)
    p = mi.traverse(mi.load_dict(d))
    buf = {
        k: [float(x) for x in p[k]] for k in ("vertex_positions", "vertex_normals", "vertex_texcoords") if k in p.keys()
    }
    buf["faces"] = [int(x) for x in p["faces"]]
    cases.append({"file": name, "shape_index": index, "face_normals": face_normals, "to_world": to_world, **buf})

(HERE / "mitsuba_reference.json").write_text(json.dumps({"mitsuba": mi.__version__, "cases": cases}, indent=1) + "\n")
print(f"wrote {len(cases)} cases")
