"""The wheel's build step (pyproject.toml has the metadata): build the plugins for the platform
(the Rust kernels once, a C++ layer per Mitsuba release of cpp/mitsuba_releases.txt published
there, and one for the installed Mitsuba when the table lacks its release) and the `matte`
binary with cpp/build_plugin.py, straight into the wheel's package; put in what the `matte`
tool reads at run time besides the ground-truth tables it already holds (the bundled scenes of
mitsuba_scenes/ as `scenes/`, with `all_types.xml` written there from the model registry just
built, the study report's BRDF slices of docs/microgeometry/ as `truth_slices/`); require the Mitsuba releases it has layers for; and tag the wheel for the
platform (it holds native code, but no Python extension: any Python 3 that runs Mitsuba can
load it). MATTE_PLATFORM=linux-aarch64 cross-builds the aarch64 wheel on x86-64."""

import glob
import os
import shutil
import subprocess
import sys

from setuptools import setup
from setuptools.command.bdist_wheel import bdist_wheel
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

ROOT = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(ROOT, "cpp"))
import build_plugin  # noqa: E402  (cpp/build_plugin.py)

TARGET = build_plugin.target_platform()
# The study report's BRDF slices (rust/matte/src/study/report/truth_section.rs: SLICES): each model's
# slice of largest error against its surface, and both surfaces at the study's roughness.
SLICES = ["truth_slice_*.png", "slices_*_r0.3_rho0.8.png"]


class BuildPlugins(build_py):
    def run(self):
        # build_py adds to what an earlier build left in build/lib, so files of a layout since
        # changed (a release no longer built, another platform's) would ship: start afresh.
        package = os.path.join(self.build_lib, "matte_mitsuba")
        shutil.rmtree(package, ignore_errors=True)
        super().run()
        subprocess.check_call(
            [sys.executable, os.path.join(ROOT, "cpp", "build_plugin.py"), "--platform", TARGET.name, "--out", package]
        )
        scenes = os.path.join(package, "scenes")
        shutil.copytree(
            os.path.join(ROOT, "mitsuba_scenes"),
            scenes,
            ignore=shutil.ignore_patterns("__pycache__", "*.pyc", "make_assets.py"),
        )
        # Every registered type in one scene, from the registry of this build (its _build.py),
        # so that no list of models is kept by hand (python/matte_mitsuba/all_types_scene.py).
        subprocess.check_call([sys.executable, os.path.join(package, "all_types_scene.py"), scenes])
        slices = os.path.join(package, "truth_slices")
        os.makedirs(slices)
        for pattern in SLICES:
            for png in glob.glob(os.path.join(ROOT, "docs", "microgeometry", pattern)):
                shutil.copy2(png, slices)


class BinaryDistribution(Distribution):
    """Native code inside: installed to platlib (`Root-Is-Purelib: false`), as auditwheel and
    the package indexes require of a wheel with shared libraries."""

    def has_ext_modules(self):
        return True


class PlatformWheel(bdist_wheel):
    def get_tag(self):
        return "py3", "none", TARGET.wheel_tag


setup(
    distclass=BinaryDistribution,
    cmdclass={"build_py": BuildPlugins, "bdist_wheel": PlatformWheel},
    install_requires=[build_plugin.requirement(TARGET), "numpy", "flip-evaluator"],
)
