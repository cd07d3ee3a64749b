"""Scenes as a user writes them: the packaged `all_types.xml` (every registered matte type, at
its defaults and its examples; written from the registry when the package is built, by
`matte_mitsuba.all_types_scene`, and not kept in the repository) loads with `import
matte_mitsuba` and renders without NaN and without any warning in every CPU variant of the
wheel (Dr.Jit's default symbolic mode), also with the `mitsuba` command-line tool and its
defaults; `reflectance` as a bitmap texture renders and shows the texture."""

import os
import re
import sys

import matte_mitsuba
import numpy as np
import pytest
from conftest import REPO
from matte_mitsuba import all_types_scene, registry

#: The installed package's scene of every registered type.
ALL_TYPES = os.path.join(matte_mitsuba.SCENES, all_types_scene.NAME)


class Capture:
    """Collects every Mitsuba log message at Warn level or above."""

    def __init__(self, mi):
        self.messages = []
        capture = self

        class Appender(mi.Appender):
            def append(self, level, text):
                if level >= mi.LogLevel.Warn:
                    capture.messages.append(text)

            def log_progress(self, *args):
                pass

        self.appender = Appender()
        self.logger = mi.logger()

    def __enter__(self):
        self.logger.add_appender(self.appender)
        return self

    def __exit__(self, *exc):
        self.logger.remove_appender(self.appender)


ALL_CPU_VARIANTS = [
    "scalar_rgb",
    "scalar_spectral",
    "scalar_spectral_polarized",
    "llvm_ad_rgb",
    "llvm_ad_mono",
    "llvm_ad_mono_polarized",
    "llvm_ad_spectral",
    "llvm_ad_spectral_polarized",
]


@pytest.mark.parametrize("mi_variant", ALL_CPU_VARIANTS, indirect=True)
def test_all_types_scene_renders_cleanly(mi_variant):
    mi = mi_variant
    with Capture(mi) as log:
        scene = mi.load_file(ALL_TYPES, spp=8, res=48)
        img = np.array(mi.render(scene, seed=1))
    assert np.isfinite(img).all(), "NaN or Inf in the image"
    assert img.mean() > 0.02, img.mean()
    # Mitsuba's own note that a mono variant writes luminance is not about matte.
    ours = [m for m in log.messages if "Monochrome mode enabled" not in m]
    assert not ours, ours
    kinds = set(re.findall(r'type = "(\w+)"', " ".join(str(s.bsdf()) for s in scene.shapes())))
    assert kinds == set(registry.NAMES), kinds


def test_all_types_scene_is_the_one_the_registry_generates():
    """The packaged `all_types.xml` (the README renders it) is what its generator writes from the
    installed registry: the build wrote it from the registry it built, and no copy of it is kept
    in the repository, where it could fall behind the registry."""
    packaged = open(ALL_TYPES).read()
    assert packaged == all_types_scene.scene_text(registry), (
        f"{ALL_TYPES} differs from the installed registry's scene: rebuild the wheel (make plugin)"
    )
    assert not os.path.exists(os.path.join(REPO, "mitsuba_scenes", all_types_scene.NAME))


@pytest.mark.parametrize("mi_variant", ["scalar_rgb", "llvm_ad_rgb"], indirect=True)
def test_bitmap_reflectance(mi_variant, tmp_path):
    mi = mi_variant
    # Left half dark, right half bright: the texture must show in the render.
    tex = np.ones((8, 8, 3), dtype=np.float32) * 0.9
    tex[:, :4] = 0.1
    path = str(tmp_path / "checker.exr")
    mi.Bitmap(tex).write(path)
    scene = mi.load_dict(
        {
            "type": "scene",
            "integrator": {"type": "direct"},
            "sensor": {
                "type": "perspective",
                "fov": 30,
                "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 4], target=[0, 0, 0], up=[0, 1, 0]),
                "film": {"type": "hdrfilm", "width": 32, "height": 32, "rfilter": {"type": "box"}},
            },
            "plane": {
                "type": "rectangle",
                "bsdf": {
                    "type": "oren_nayar",
                    "reflectance": {"type": "bitmap", "filename": path, "filter_type": "nearest"},
                },
            },
            "light": {"type": "constant", "radiance": 1.0},
        }
    )
    img = np.array(mi.render(scene, spp=16))
    assert np.isfinite(img).all()
    left, right = img[12:20, 4:12].mean(), img[12:20, 20:28].mean()
    assert right > 4 * left, (left, right)


def test_mitsuba_command_line_tool_with_its_defaults(tmp_path):
    """`mitsuba -a <plugins> scene.xml`: the tool's default variant and mode (llvm, symbolic)."""
    import subprocess

    root = subprocess.run(
        [sys.executable, "-m", "matte_mitsuba"], capture_output=True, text=True, check=True
    ).stdout.strip()
    out = str(tmp_path / "all_types.exr")
    tool = os.path.join(os.path.dirname(sys.executable), "mitsuba")
    run = subprocess.run(
        [tool, "-a", root, "-D", "spp=4", "-D", "res=32", "-o", out, ALL_TYPES],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    img = np.array(mi.Bitmap(out))
    assert np.isfinite(img).all() and img[..., :3].mean() > 0.02, img.mean()


@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_study_scene_curved_with_table_models(mi_variant):
    """The study's `curved` scene with every diffuse surface `ginneken` (both samplers) and
    `tabulated_brdf` renders, finite, in symbolic llvm: the table gathers' indices stay inside
    their tables on every lane, whatever an inactive lane's directions hold (an unclamped packet
    index once read outside the slope table here and crashed the process)."""
    from validation import sampling_scenes  # the scene with its `$bsdf` surfaces substituted

    mi = mi_variant
    path = sampling_scenes.SCENES["curved"]
    table = os.path.join(REPO, "python", "matte_mitsuba", "ground_truth", "height_field_m0.3.json")
    mi.file_resolver().prepend(os.path.dirname(os.path.join(REPO, path)))
    for kind, params in (
        ("ginneken", {"sampling": "cosine"}),
        ("ginneken", {"sampling": "cltc"}),
        ("tabulated_brdf", {"filename": table}),
    ):
        scene = mi.load_string(sampling_scenes.scene_text(path, kind, params), spp="16", res="96")
        img = np.array(mi.render(scene, seed=1))
        assert np.isfinite(img).all(), kind
        assert img.mean() > 0.01, (kind, img.mean())
