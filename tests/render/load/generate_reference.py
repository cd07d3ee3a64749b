#!/usr/bin/env python3
"""Writes tests/render/load/references.rs: what Mitsuba 3.9.1 (scalar_rgb) gives for the
scenes of the loader's tests (tests/render/load/*.rs), which those tests compare matte with.
Run by hand with the venv's Python from the repository root (a few seconds):

    .venv/bin/python tests/render/load/generate_reference.py          # rewrite the file
    .venv/bin/python tests/render/load/generate_reference.py --check  # regenerate and diff

`--check` writes nothing: it prints the difference between the file and what Mitsuba gives
now and exits 1 if there is one.

Each case loads the test's XML (or the same plugin with the same properties) with
`mi.load_string` / `mi.load_file` and asks the loaded object. Covered (test → what Mitsuba is
asked):

* sensor.rs `camera_ray_matches_the_verified_example`, `near_far_clip_principal_point_and_to_world`:
  `sensor.sample_ray` at film corners and centres (position sample = pixel / film size).
* sensor.rs `default_focal_length_gives_38_1848_degrees_at_4_to_3`,
  `fov_axis_converts_with_the_full_film_aspect`: `mi.traverse(sensor)['x_fov']`, film size.
* shape.rs `nested_includes_resolve_paths_like_mitsuba`: the same file layout through
  `mi.load_file`: the scene loads and the triangle is hit; with `tri.obj` alone it fails
  ("file not found").
* emitter.rs `area_emitter_colours`, `point_spot_directional_constant` (the `<spectrum value="1">`
  intensity and radiance, positions, defaults): `emitter.eval` / `mi.traverse`.
* emitter.rs `emitter_selection_follows_mitsubas_scene_order`: `scene.emitters()` with
  `parallel=False`, the most frequent order of 100 loads (about 5–8 % of loads list the
  rectangles' emitters as shape3, shape4, shape1 instead of shape4, shape3, shape1).
* emitter.rs `emitter_positions_map_the_sample_as_mitsuba`: `shape.sample_position` on the
  transformed rectangle and on the two-triangle OBJ.
* bsdf.rs `diffuse_reflectance_colours`: `mi.traverse(bsdf)['reflectance.value']`.
* bsdf.rs `null_bsdf_passes_rays_straight_through`: `null`'s sample; `twosided` around it.
* bsdf.rs `mask_defaults_and_errors`: the default opacity.
* bsdf.rs `dielectric_iors_and_weights`: `eta`, and `bsdf.sample` weights for reflection (ξ = 0)
  and refraction (ξ = 0.999) at normal incidence.
* bsdf.rs `conductors_fresnel_at_normal_incidence`, `roughconductor_defaults_and_roughness`: the
  sample weight / eval ratio at normal incidence; the `roughconductor` defaults as its
  `to_string` prints them.
* texture.rs `bitmap_reflectance_nested_and_referenced`: the 2×2 red, green / blue, grey PNG as
  `reflectance` (bilinear, nearest, raw + clamp).
* texture.rs `checkerboard_texture`, `checkerboard_eval_1_swaps_the_colours`: `eval` on the
  rectangle through `to_uv`, defaults, and `eval` / `eval_1` / `mean` of color0 = (0.9, 0.1, 0.2),
  color1 = 0.3.
* texture.rs `rawconstant_texture`: its value, unconverted.
"""

import difflib
import json
import sys
import tempfile
from pathlib import Path

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)
OUT = Path(__file__).resolve().parent / "references.rs"
TMP = Path(tempfile.mkdtemp(prefix="matte-load-ref-"))
SENSOR = (
    '<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/>'
    '<integer name="height" value="2"/></film></sensor>'
)
ITEMS = []


def f32(x):
    """An f32 literal: the shortest decimal that reads back as Mitsuba's f32."""
    s = str(np.float32(x))
    return s if any(c in s for c in ".en") else s + ".0"


def arr(v):
    return "[" + ", ".join(f32(c) for c in v) + "]"


def string(s):
    return json.dumps(s, ensure_ascii=False)


def const(name, ty, value, doc):
    """`pub const name: ty = value;` with its doc comment."""
    ITEMS.append((name, ty, value, doc))


def load(body, **kw):
    return mi.load_string(f'<scene version="3.0.0">{body}</scene>', **kw)


def one(xml):
    """One plugin from its XML element."""
    return mi.load_string(xml.replace(" type=", ' version="3.0.0" type=', 1))


def vec(v):
    return [float(c) for c in v]


def si_at(uv=(0.5, 0.5), wi=(0.0, 0.0, 1.0)):
    si = mi.SurfaceInteraction3f()
    si.uv = list(uv)
    si.wi = list(wi)
    si.sh_frame = mi.Frame3f([0.0, 0.0, 1.0])
    si.n = [0.0, 0.0, 1.0]
    return si


def fails(load_it, needle):
    """Whether loading fails with `needle` in Mitsuba's message (any other failure is a bug here)."""
    try:
        load_it()
    except Exception as e:  # noqa: BLE001
        assert needle in str(e), str(e)
        return True
    return False


def rust_bool(b):
    return "true" if b else "false"


CTX = mi.BSDFContext()

# ----------------------------------------------------------------------------------------------
# Sensor (§4)


def camera(props, w, h):
    return one(
        f'<sensor type="perspective">{props}<film type="hdrfilm"><integer name="width" value="{w}"/>'
        f'<integer name="height" value="{h}"/></film></sensor>'
    )


def ray(cam, px, py, w, h):
    """`CameraRay { o, d, maxt }` of Mitsuba's ray through film pixel (px, py)."""
    r, _ = cam.sample_ray(0.0, 0.5, [px / w, py / h], [0.5, 0.5])
    return f"CameraRay {{ o: {arr(vec(r.o))}, d: {arr(vec(r.d))}, maxt: {f32(r.maxt)} }}"


cam = camera(
    '<float name="fov" value="90"/><transform name="to_world"><lookat origin="0,0,5" target="0,0,0" '
    'up="0,1,0"/></transform>',
    4,
    2,
)
const(
    "CAMERA_CORNER",
    "CameraRay",
    ray(cam, 0, 0, 4, 2),
    "fov 90, at (0, 0, 5) looking at the origin, 4×2 film: the ray through film corner (0, 0).",
)
const("CAMERA_CENTRE", "CameraRay", ray(cam, 2, 1, 4, 2), "The same camera's ray through the film centre (2, 1).")
const("CAMERA_OPPOSITE_CORNER", "CameraRay", ray(cam, 4, 2, 4, 2), "The same camera's ray through film corner (4, 2).")

p = mi.traverse(one('<sensor type="perspective"/>'))
size = vec(p["film.size"])
const(
    "DEFAULT_FILM_SIZE", "(u32, u32)", f"({int(size[0])}, {int(size[1])})", "A bare `perspective` sensor's film size."
)
const(
    "DEFAULT_X_FOV",
    "f64",
    repr(float(np.float32(p["x_fov"]))),
    "A bare `perspective` sensor's x_fov in degrees (focal_length 50mm).",
)
rows = []
for axis in ["x", "y", "diagonal", "smaller", "larger", "Y"]:
    cam = camera(f'<float name="fov" value="45"/><string name="fov_axis" value="{axis}"/>', 768, 576)
    rows.append(f"({string(axis)}, {repr(float(np.float32(mi.traverse(cam)['x_fov'])))})")
const(
    "FOV_45_X_FOV",
    "&[(&str, f64)]",
    "&[" + ", ".join(rows) + "]",
    "fov 45 along `fov_axis` at 768×576: (fov_axis, x_fov in degrees).",
)
rows = []
for axis in ["larger", "smaller"]:
    cam = camera(f'<float name="fov" value="45"/><string name="fov_axis" value="{axis}"/>', 576, 768)
    rows.append(f"({string(axis)}, {f32(np.tan(np.radians(mi.traverse(cam)['x_fov']) / 2))})")
const(
    "FOV_45_PORTRAIT_TAN_HALF",
    "&[(&str, f32)]",
    "&[" + ", ".join(rows) + "]",
    "fov 45 along `fov_axis` at 576×768 (portrait): (fov_axis, tan(x_fov / 2)).",
)

cam = camera(
    '<float name="fov" value="90"/><float name="near_clip" value="0.5"/><float name="far_clip" value="20"/>', 4, 2
)
const(
    "NEAR_FAR_CENTRE",
    "CameraRay",
    ray(cam, 2, 1, 4, 2),
    "fov 90, near_clip 0.5, far_clip 20, 4×2 film: the ray through the centre.",
)
const("NEAR_FAR_CORNER", "CameraRay", ray(cam, 0, 0, 4, 2), "The same camera's ray through corner (0, 0).")
off = camera(
    '<float name="fov" value="60"/><float name="principal_point_offset_x" value="0.25"/>'
    '<float name="principal_point_offset_y" value="-0.125"/>',
    8,
    4,
)
const(
    "PRINCIPAL_POINT_CENTRE",
    "CameraRay",
    ray(off, 4, 2, 8, 4),
    "fov 60, principal point offset (0.25, −0.125), 8×4 film: the ray through the centre.",
)
const(
    "PLAIN_AT_SHIFTED_CENTRE",
    "CameraRay",
    ray(camera('<float name="fov" value="60"/>', 8, 4), 6, 1.5, 8, 4),
    "fov 60 without offset, 8×4 film: the ray through (6, 1.5), where the offset moves the centre.",
)
cam = camera(
    '<float name="fov" value="90"/><transform name="to_world"><rotate y="1" angle="90"/>'
    '<translate x="1" y="2" z="3"/></transform>',
    4,
    2,
)
const(
    "TURNED_CAMERA_CENTRE",
    "CameraRay",
    ray(cam, 2, 1, 4, 2),
    "fov 90, rotated +90° about y, then moved to (1, 2, 3), 4×2 film: the ray through the centre.",
)

# ----------------------------------------------------------------------------------------------
# Shapes: nested_includes_resolve_paths_like_mitsuba

root = TMP / "nested_paths"
for d in ["x/y/include", "common", "meshes"]:
    (root / d).mkdir(parents=True, exist_ok=True)
(root / "meshes/tri.obj").write_text("v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n")
(root / "x/y/include/inc.xml").write_text(
    '<scene version="3.0.0">\n<path value="../../common"/>\n<include filename="mat.xml"/>\n</scene>'
)
(root / "common/mat.xml").write_text(
    '<scene version="3.0.0">\n<path value="../meshes"/>\n<bsdf type="diffuse" id="m"/>\n</scene>'
)


def main_xml(mesh):
    return (
        f'<scene version="3.0.0">\n{SENSOR}\n<include filename="include/inc.xml"/>\n'
        f'<shape type="obj"><string name="filename" value="{mesh}"/><ref id="m"/></shape>\n</scene>'
    )


main = root / "x/y/main.xml"
main.write_text(main_xml("../../meshes/tri.obj"))
scene = mi.load_file(str(main))
hit = bool(scene.ray_intersect(mi.Ray3f([0, 0, 1], [0, 0, -1])).is_valid())
const(
    "NESTED_INCLUDES_FIND_THE_MESH",
    "bool",
    rust_bool(hit),
    "The mesh found through nested `<include>`s and `<path>`s: the scene loads and the triangle is hit.",
)
main.write_text(main_xml("tri.obj"))
const(
    "INCLUDED_PATH_OUTLIVES_ITS_FILE",
    "bool",
    rust_bool(not fails(lambda: mi.load_file(str(main)), "file not found")),
    'Whether a `<path>` given in an included file still holds after it (Mitsuba: "file not found").',
)

# ----------------------------------------------------------------------------------------------
# Emitters (§2, §5, §9)

rows = []
for prop in [
    '<spectrum name="radiance" value="1"/>',
    '<spectrum name="radiance" value="2"/>',
    '<rgb name="radiance" value="6 6 5"/>',
    '<float name="radiance" value="3"/>',
    "",
    '<spectrum name="radiance" value="360:0.5 830:0.5"/>',
]:
    scene = load(f'<shape type="rectangle"><emitter type="area">{prop}</emitter></shape>')
    rows.append(f"({string(prop)}, {arr(vec(scene.emitters()[0].eval(si_at())))})")
const(
    "AREA_RADIANCE",
    "&[(&str, [f32; 3])]",
    "&[" + ", ".join(rows) + "]",
    "An `area` emitter on a rectangle: (its radiance property, the radiance it emits).",
)
emitter = one(
    '<emitter type="point"><transform name="to_world"><translate x="-1" y="4"/></transform>'
    '<spectrum name="intensity" value="1"/></emitter>'
)
p = mi.traverse(emitter)
const(
    "POINT_POSITION_FROM_TO_WORLD",
    "[f32; 3]",
    arr(vec(p["position"])),
    "A `point` emitter translated by (−1, 4, 0): its position.",
)
const(
    "POINT_SPECTRUM_1_INTENSITY",
    "[f32; 3]",
    arr(vec(p["intensity.value"])),
    'A `point` emitter\'s `<spectrum name="intensity" value="1"/>`.',
)
const(
    "POINT_DEFAULT_POSITION",
    "[f32; 3]",
    arr(vec(mi.traverse(one('<emitter type="point"/>'))["position"])),
    "A bare `point` emitter's position.",
)
const(
    "CONSTANT_DEFAULT_RADIANCE",
    "[f32; 3]",
    arr(vec(one('<emitter type="constant"/>').eval(si_at(wi=(0, 0, -1))))),
    "A bare `constant` emitter's radiance.",
)
const(
    "CONSTANT_SPECTRUM_1_RADIANCE",
    "[f32; 3]",
    arr(
        vec(one('<emitter type="constant"><spectrum name="radiance" value="1"/></emitter>').eval(si_at(wi=(0, 0, -1))))
    ),
    'A `constant` emitter\'s `<spectrum name="radiance" value="1"/>`.',
)


def area(shape, x):
    return (
        f'<shape type="{shape}"><transform name="to_world"><translate x="{x}"/></transform>'
        '<emitter type="area"/></shape>'
    )


body = "\n".join(
    [
        area("sphere", 0),
        area("rectangle", 1),
        '<emitter type="constant"/>',
        area("sphere", 2),
        area("rectangle", 3),
        '<emitter type="point"/>',
        area("rectangle", 4),
    ]
)
orders = {}
for _ in range(100):  # not fully deterministic even with parallel=False: ~5-8 % of loads swap shape4 and shape3
    scene = load(f"{SENSOR}\n{body}", parallel=False)
    names = []
    for e in scene.emitters():
        shape = e.get_shape()
        if shape is not None:
            names.append(f"shape{int(round(float(shape.bbox().center()[0])))}")
        else:
            names.append("constant" if "Constant" in e.class_name() else "point")
    orders[tuple(names)] = orders.get(tuple(names), 0) + 1
order = max(orders, key=orders.get)
const(
    "EMITTER_ORDER",
    "&[&str]",
    "&[" + ", ".join(string(n) for n in order) + "]",
    "`scene.emitters()` (`parallel=False`, the most frequent of 100 loads) of spheres and rectangles at "
    "x = 0…4 with area emitters, a `constant` after the first two and a `point` after the fourth "
    "(`shapeN`: the shape at x = N).",
)

obj = TMP / "two.obj"
obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 1\nv 8 0 1\nv 5 1 1\nf 1 2 3\nf 4 5 6\n")
scene = load(
    f'{SENSOR}<shape type="rectangle"><transform name="to_world"><scale x="2" y="0.5"/>'
    '<rotate x="1" angle="90"/><translate z="3"/></transform></shape>'
    f'<shape type="obj"><string name="filename" value="{obj}"/></shape>'
)
rect = next(s for s in scene.shapes() if s.bbox().center()[2] > 2)
mesh = next(s for s in scene.shapes() if s.bbox().center()[2] < 2)
rows = []
for u in [(0.1, 0.7), (0.9, 0.2), (0.5, 0.5)]:
    ps = rect.sample_position(0.0, list(u))
    rows.append(f"SamplePosition {{ u: {arr(u)}, p: {arr(vec(ps.p))}, n: {arr(vec(ps.n))}, uv: {arr(vec(ps.uv))} }}")
const(
    "RECTANGLE_SAMPLE_POSITION",
    "&[SamplePosition]",
    "&[" + ", ".join(rows) + "]",
    "`sample_position` on the rectangle scaled by (2, 0.5), turned +90° about x and moved to z = 3.",
)
rows = []
for x in (0.05, 0.95):
    for y in (0.2, 0.3):
        rows.append(f"({arr((x, y))}, {f32(mesh.sample_position(0.0, [x, y]).p[2])})")
const(
    "TWO_TRIANGLE_SAMPLE_Z",
    "&[([f32; 2], f32)]",
    "&[" + ", ".join(rows) + "]",
    "`sample_position` on the OBJ of two triangles, area 1/2 at z = 0 and 3/2 at z = 1: (sample, z).",
)

# ----------------------------------------------------------------------------------------------
# BSDFs (§2, §10)

rows = []
for prop in [
    "",
    '<rgb name="reflectance" value="0.2, 0.4, 0.6"/>',
    '<float name="reflectance" value="0.7"/>',
    '<float name="reflectance" value="1.5"/>',
    '<spectrum name="reflectance" value="0.3"/>',
    '<spectrum name="reflectance" value="360:0.5 830:0.5"/>',
]:
    value = mi.traverse(one(f'<bsdf type="diffuse">{prop}</bsdf>'))["reflectance.value"]
    rows.append(f"({string(prop)}, {arr(vec(value) if hasattr(value, '__len__') else [value] * 3)})")
const(
    "DIFFUSE_REFLECTANCE",
    "&[(&str, [f32; 3])]",
    "&[" + ", ".join(rows) + "]",
    "`diffuse`: (its reflectance property, the reflectance it holds).",
)

b = one('<bsdf type="null"/>')
bs, w = b.sample(CTX, si_at(wi=[0.3, 0.0, 0.954]), 0.3, [0.2, 0.7])
const(
    "NULL_SAMPLE",
    "([f32; 3], [f32; 3], f32, bool)",
    f"({arr(vec(bs.wo))}, {arr(vec(w))}, {f32(bs.pdf)}, {rust_bool(mi.has_flag(bs.sampled_type, mi.BSDFFlags.Null))})",
    "`null` sampled at wi = (0.3, 0, 0.954): (wo, weight, pdf, whether the sampled lobe is a null one, "
    "which passes the ray on).",
)
const(
    "TWOSIDED_AROUND_NULL_REFUSED",
    "bool",
    rust_bool(fails(lambda: one('<bsdf type="twosided"><bsdf type="null"/></bsdf>'), "transmission")),
    'Whether `twosided` refuses a nested `null` ("Only materials without a transmission component can be nested!").',
)
scene = load(f'{SENSOR}<shape type="rectangle"><bsdf type="mask"><bsdf type="diffuse"/></bsdf></shape>')
opacity = [v for k, v in mi.traverse(scene).items() if k.endswith("opacity.value")][0]
const("MASK_DEFAULT_OPACITY", "f32", f32(opacity), "A `mask` without `opacity`: its opacity.")

rows = []
for props in [
    "",
    '<string name="int_ior" value="water"/><string name="ext_ior" value="Vacuum"/>',
    '<float name="int_ior" value="1"/><float name="ext_ior" value="1.33"/>',
]:
    eta = mi.traverse(one('<bsdf type="dielectric">' + props + "</bsdf>"))["eta"]
    rows.append(f"({string(props)}, {f32(eta)})")
const(
    "DIELECTRIC_ETA",
    "&[(&str, f32)]",
    "&[" + ", ".join(rows) + "]",
    "`dielectric`: (its ior properties, η = int_ior / ext_ior).",
)
b = one(
    '<bsdf type="dielectric"><float name="int_ior" value="1.5"/><float name="ext_ior" value="1"/>'
    '<rgb name="specular_reflectance" value="0.5 0.6 0.7"/><float name="specular_transmittance" value="0.9"/></bsdf>'
)
bs, w = b.sample(CTX, si_at(), 0.0, [0.0, 0.0])
const(
    "DIELECTRIC_REFLECTION",
    "([f32; 3], [f32; 3])",
    f"({arr(vec(bs.wo))}, {arr(vec(w))})",
    "`dielectric` 1.5 / 1 with specular_reflectance (0.5, 0.6, 0.7) and specular_transmittance 0.9, sampled at normal incidence with ξ = 0 (reflection): (wo, weight).",
)
bs, w = b.sample(CTX, si_at(), 0.999, [0.0, 0.0])
const(
    "DIELECTRIC_REFRACTION",
    "([f32; 3], [f32; 3])",
    f"({arr(vec(bs.wo))}, {arr(vec(w))})",
    "The same with ξ = 0.999 (refraction): (wo, weight).",
)


def f0(xml):
    return arr(vec(one(xml).sample(CTX, si_at(), 0.5, [0.5, 0.5])[1]))


const(
    "CONDUCTOR_DEFAULT_F0",
    "[f32; 3]",
    f0('<bsdf type="conductor"/>'),
    "A bare `conductor` (material none) at normal incidence: its sample weight F(0).",
)
const(
    "CONDUCTOR_AU_F0",
    "[f32; 3]",
    f0('<bsdf type="conductor"><string name="material" value="Au"/></bsdf>'),
    "`conductor` Au: F(0).",
)
const(
    "CONDUCTOR_ETA_K_F0",
    "[f32; 3]",
    f0(
        '<bsdf type="conductor"><float name="eta" value="1.5"/><float name="k" value="0"/>'
        '<rgb name="specular_reflectance" value="1 0.5 0.25"/></bsdf>'
    ),
    "`conductor` eta 1.5, k 0, specular_reflectance (1, 0.5, 0.25): F(0).",
)
const(
    "CONDUCTOR_NONE_ETA_K_F0",
    "[f32; 3]",
    f0(
        '<bsdf type="conductor"><string name="material" value="none"/><float name="eta" value="1.5"/>'
        '<float name="k" value="0"/></bsdf>'
    ),
    "`conductor` material none spelt out, eta 1.5, k 0: F(0).",
)
rc = one('<bsdf type="roughconductor"/>')
text = str(rc)
fields = {
    line.split("=")[0].strip(): line.split("=", 1)[1].strip().rstrip(",") for line in text.splitlines() if "=" in line
}
alpha = lambda s: s.split("value=")[1].rstrip("]")  # noqa: E731  # UniformSpectrum[value=0.100000]
distribution = {"beckmann": "Beckmann", "ggx": "Ggx"}[fields["distribution"]]
const(
    "ROUGHCONDUCTOR_DEFAULTS",
    "(MicrofacetDistribution, f32, f32, bool)",
    f"(MicrofacetDistribution::{distribution}, {f32(float(alpha(fields['alpha_u'])))}, "
    f"{f32(float(alpha(fields['alpha_v'])))}, {rust_bool(fields['sample_visible'] == '1')})",
    "A bare `roughconductor` as its `to_string` prints it: (distribution, alpha_u, alpha_v, sample_visible).",
)
au = one('<bsdf type="roughconductor"><string name="material" value="Au"/></bsdf>')
ratio = np.array(vec(au.eval(CTX, si_at(), [0, 0, 1]))) / np.array(vec(rc.eval(CTX, si_at(), [0, 0, 1])))
const(
    "ROUGHCONDUCTOR_AU_OVER_MIRROR",
    "[f32; 3]",
    arr(ratio),
    "`roughconductor` Au over the bare (mirror) one, `eval` at wi = wo = n.",
)

# ----------------------------------------------------------------------------------------------
# Textures (§2, §11)

png = TMP / "tex.png"
mi.Bitmap(np.array([[[255, 0, 0], [0, 255, 0]], [[0, 0, 255], [128, 128, 128]]], dtype=np.uint8)).write(str(png))


def bitmap(extra=""):
    return one(f'<texture type="bitmap"><string name="filename" value="{png}"/>{extra}</texture>')


const(
    "BITMAP_BILINEAR_CENTRE",
    "[f32; 3]",
    arr(vec(bitmap().eval(si_at((0.5, 0.5))))),
    "The 2×2 PNG (red, green / blue, grey 128) as a `bitmap`: `eval` at uv (0.5, 0.5).",
)
t = bitmap('<string name="filter_type" value="nearest"/>')
rows = [
    f"({arr(uv)}, {arr(vec(t.eval(si_at(uv))))})"
    for uv in [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75), (1.25, 0.25)]
]
const(
    "BITMAP_NEAREST",
    "&[([f32; 2], [f32; 3])]",
    "&[" + ", ".join(rows) + "]",
    "The same PNG with filter_type nearest: (uv, `eval`).",
)
t = bitmap(
    '<boolean name="raw" value="true"/><string name="filter_type" value="nearest"/>'
    '<string name="wrap_mode" value="clamp"/>'
)
rows = [f"({arr(uv)}, {arr(vec(t.eval(si_at(uv))))})" for uv in [(0.75, 0.75), (1.75, 0.25)]]
const(
    "BITMAP_RAW_CLAMP",
    "&[([f32; 2], [f32; 3])]",
    "&[" + ", ".join(rows) + "]",
    "The same PNG, raw, nearest, wrap_mode clamp: (uv, `eval`).",
)


def reflectance_at(scene, x, y):
    si = scene.ray_intersect(mi.Ray3f([x, y, 1.0], [0.0, 0.0, -1.0]))
    return vec(si.bsdf().eval_diffuse_reflectance(si))


scene = load(
    f'{SENSOR}<shape type="rectangle"><bsdf type="diffuse"><texture type="checkerboard" name="reflectance">'
    '<rgb name="color0" value="0.9"/><rgb name="color1" value="0.1, 0.2, 0.3"/>'
    '<transform name="to_uv"><scale x="2" y="2"/></transform></texture></bsdf></shape>'
)
points = [(-0.75, -0.75), (-0.25, -0.75), (-0.25, -0.25), (0.25, -0.75), (0.75, -0.25), (0.75, -0.75), (0.75, 0.75)]
rows = [f"({f32(x)}, {f32(y)}, {arr(reflectance_at(scene, x, y))})" for x, y in points]
const(
    "CHECKERBOARD_SCALED",
    "&[(f32, f32, [f32; 3])]",
    "&[" + ", ".join(rows) + "]",
    "A `checkerboard` (color0 0.9, color1 (0.1, 0.2, 0.3), to_uv scale 2) as the reflectance of the "
    "rectangle, seen straight down at (x, y): (x, y, reflectance).",
)
scene = load(
    f'{SENSOR}<shape type="rectangle"><bsdf type="diffuse"><texture type="checkerboard" '
    'name="reflectance"/></bsdf></shape>'
)
rows = [f"({f32(x)}, {f32(y)}, {arr(reflectance_at(scene, x, y))})" for x, y in [(-0.75, -0.75), (0.25, -0.75)]]
const(
    "CHECKERBOARD_DEFAULTS",
    "&[(f32, f32, [f32; 3])]",
    "&[" + ", ".join(rows) + "]",
    "A bare `checkerboard` the same way: (x, y, reflectance).",
)
t = one(
    '<texture type="checkerboard"><rgb name="color0" value="0.9, 0.1, 0.2"/><float name="color1" value="0.3"/></texture>'
)
rows = [
    f"({arr(uv)}, {arr(vec(t.eval(si_at(uv))))}, {f32(t.eval_1(si_at(uv)))})"
    for uv in [(0.25, 0.25), (0.75, 0.25), (0.75, 0.75), (1.25, 0.75)]
]
const(
    "CHECKERBOARD_EVAL",
    "&[([f32; 2], [f32; 3], f32)]",
    "&[" + ", ".join(rows) + "]",
    "A `checkerboard` of color0 (0.9, 0.1, 0.2) and color1 0.3: (uv, `eval`, `eval_1`).",
)
const("CHECKERBOARD_MEAN", "f32", f32(t.mean()), "The same checkerboard's `mean()`.")
t = one('<texture type="rawconstant"><vector name="value" value="0.5, 0.25, 1"/></texture>')
const(
    "RAWCONSTANT_VECTOR",
    "[f32; 3]",
    arr(vec(t.eval(si_at()))),
    '`rawconstant` with `<vector name="value" value="0.5, 0.25, 1"/>`: `eval`.',
)
t = one('<texture type="rawconstant"><float name="value" value="0.3"/></texture>')
const(
    "RAWCONSTANT_FLOAT",
    "[f32; 3]",
    arr(vec(t.eval(si_at()))),
    '`rawconstant` with `<float name="value" value="0.3"/>`: `eval`.',
)


# ----------------------------------------------------------------------------------------------


def wrap(text, prefix):
    words, lines, cur = text.split(), [], prefix
    for w in words:
        if len(cur) + 1 + len(w) > 100 and cur != prefix:
            lines.append(cur)
            cur = prefix + " " + w
        else:
            cur += " " + w
    lines.append(cur)
    return "\n".join(lines)


def render():
    out = [
        "//! Generated by `tests/render/load/generate_reference.py`; do not edit (rerun it).",
        wrap(
            "What Mitsuba 3.9.1 (`scalar_rgb`, PyPI wheel `mitsuba==3.9.1`) gives for the scenes of the "
            "loader's tests in this folder, which they compare matte with (the script says which test "
            "asks what).",
            "//!",
        ),
        "",
        "use matte_render::bsdf::MicrofacetDistribution;",
        "",
        "/// A camera ray: origin, direction, length.",
        "pub struct CameraRay {",
        "    pub o: [f32; 3],",
        "    pub d: [f32; 3],",
        "    pub maxt: f32,",
        "}",
        "",
        "/// A point drawn on a shape from the sample `u`: position, normal, uv.",
        "pub struct SamplePosition {",
        "    pub u: [f32; 2],",
        "    pub p: [f32; 3],",
        "    pub n: [f32; 3],",
        "    pub uv: [f32; 2],",
        "}",
    ]
    for name, ty, value, doc in ITEMS:
        out += ["", wrap(doc, "///"), f"pub const {name}: {ty} = {value};"]
    return "\n".join(out) + "\n"


text = render()
if "--check" in sys.argv[1:]:
    old = OUT.read_text() if OUT.exists() else ""
    diff = list(difflib.unified_diff(old.splitlines(), text.splitlines(), str(OUT), "Mitsuba now", lineterm=""))
    print("\n".join(diff) if diff else f"{OUT.name}: what Mitsuba gives")
    sys.exit(1 if diff else 0)
OUT.write_text(text)
print(f"wrote {OUT} ({len(ITEMS)} references)")
