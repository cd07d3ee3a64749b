"""Converts the Stanford bunny of the npm package `bunny` (1.0.1, by Mikola Lysenko, licence
"Public Domain" in its package.json; data from the Stanford 3D Scanning Repository; see
README.md here) into `bunny.ply` for the study's bunny scene (stdlib only).

    python3 mitsuba_scenes/study/assets/make_bunny.py [PACKAGE]

PACKAGE is the tarball that `npm pack bunny` writes, or its unpacked folder (the one with
`index.js`); without it the script runs `npm pack bunny` in a temporary folder. The
package's `index.js` is `exports.positions=[[x,y,z],...]` and `exports.cells=[[i,j,k],...]`,
both plain JSON arrays, read here without running JavaScript.

What the script does to the mesh:
* Checks it is a closed two-manifold with consistent winding (every directed edge once, and
  its reverse once) and that its signed volume is positive, i.e. counter-clockwise faces
  seen from outside, which is Mitsuba's front side (geometric normal cross(p1-p0, p2-p0),
  docs/renderer-semantics.md section 8). Were the volume negative, the faces would be reversed.
* The package's +y is up already (the bunny sits on y = 0). It is scaled to height 1, its
  base put on y = 0 and its footprint centred on x = z = 0.
* Writes a binary (little-endian) PLY with float32 positions and faces only: Mitsuba (and
  matte) then compute smooth, angle-weighted vertex normals. Binary, because Mitsuba warns
  that ASCII PLY is slow to parse.
"""

import json
import re
import struct
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent


def read_index_js(text):
    arrays = dict(re.findall(r"exports\.(\w+)\s*=\s*(\[.*?\]\])", text, re.S))
    if "positions" not in arrays or "cells" not in arrays:
        sys.exit("make_bunny: index.js has no exports.positions / exports.cells")
    return json.loads(arrays["positions"]), json.loads(arrays["cells"])


def load_package(arg):
    if arg is None:
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run(["npm", "pack", "bunny@1.0.1"], cwd=tmp, check=True, capture_output=True)
            return load_package(next(Path(tmp).glob("bunny-*.tgz")))
    path = Path(arg)
    if path.is_dir():
        pkg = json.loads((path / "package.json").read_text())
        return pkg, read_index_js((path / "index.js").read_text())
    with tarfile.open(path) as tar:
        pkg = json.load(tar.extractfile("package/package.json"))
        return pkg, read_index_js(tar.extractfile("package/index.js").read().decode())


def signed_volume(pos, cells):
    vol = 0.0
    for a, b, c in cells:
        p0, p1, p2 = pos[a], pos[b], pos[c]
        vol += (
            p0[0] * (p1[1] * p2[2] - p1[2] * p2[1])
            + p0[1] * (p1[2] * p2[0] - p1[0] * p2[2])
            + p0[2] * (p1[0] * p2[1] - p1[1] * p2[0])
        ) / 6
    return vol


def check_closed(cells):
    edges = set()
    for t in cells:
        for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            if e in edges:
                sys.exit(f"make_bunny: directed edge {e} used twice: inconsistent winding")
            edges.add(e)
    if not all((b, a) in edges for a, b in edges):
        sys.exit("make_bunny: the mesh has boundary edges")


def main():
    pkg, (pos, cells) = load_package(sys.argv[1] if len(sys.argv) > 1 else None)
    check_closed(cells)
    if signed_volume(pos, cells) < 0:
        cells = [(a, c, b) for a, b, c in cells]
    lo = [min(p[i] for p in pos) for i in range(3)]
    hi = [max(p[i] for p in pos) for i in range(3)]
    s = 1.0 / (hi[1] - lo[1])
    centre = [(lo[i] + hi[i]) / 2 for i in range(3)]
    out = [((x - centre[0]) * s, (y - lo[1]) * s, (z - centre[2]) * s) for x, y, z in pos]
    vol = signed_volume(out, cells)
    assert vol > 0
    header = [
        "ply",
        "format binary_little_endian 1.0",
        f"comment Stanford bunny from the npm package {pkg['name']} {pkg['version']} "
        f"(licence: {pkg['license']}), converted by make_bunny.py",
        "comment height 1, base on y = 0, centred on x = z = 0; CCW faces seen from outside",
        f"element vertex {len(out)}",
        "property float x",
        "property float y",
        "property float z",
        f"element face {len(cells)}",
        "property list uchar int vertex_indices",
        "end_header",
    ]
    body = b"".join(struct.pack("<3f", *p) for p in out)
    body += b"".join(struct.pack("<B3i", 3, *t) for t in cells)
    (HERE / "bunny.ply").write_bytes(("\n".join(header) + "\n").encode() + body)
    print(
        f"bunny.ply: {len(out)} vertices, {len(cells)} triangles, volume {vol:.5f}, "
        f"extent x {(hi[0] - lo[0]) * s:.4f} z {(hi[2] - lo[2]) * s:.4f}"
    )


if __name__ == "__main__":
    main()
