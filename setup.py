"""The wheel's build step (pyproject.toml has the metadata): build the plugins (the Rust kernels
once, a C++ layer per Mitsuba release of cpp/mitsuba_releases.txt) and the `matte` binary with
cpp/build_plugin.sh, put into the package what the `matte` tool reads at run time besides the
ground-truth tables it already holds (the binary, the bundled scenes of mitsuba_scenes/ as
`scenes/`, the study report's BRDF slices of docs/microgeometry/ as `truth_slices/`), and tag
the wheel for this platform (it holds native code, but no Python extension: any Python 3 that
runs Mitsuba can load it)."""

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
# The study report's BRDF slices (rust/study/report/truth_section.rs: SLICES): each model's
# slice of largest error against its surface, and both surfaces at the study's roughness.
SLICES = ["truth_slice_*.png", "slices_*_r0.3_rho0.8.png"]


class BuildPlugins(build_py):
    def run(self):
        subprocess.check_call(
            [os.path.join(ROOT, "cpp", "build_plugin.sh")], env={**os.environ, "MATTE_PYTHON": sys.executable}
        )
        binary = os.path.join(ROOT, "python", "matte_mitsuba", "bin", "matte")
        os.makedirs(os.path.dirname(binary), exist_ok=True)
        shutil.copy2(os.path.join(ROOT, "target", "release", "matte"), binary)
        subprocess.check_call(["strip", binary])
        package = os.path.join(ROOT, "python", "matte_mitsuba")
        scenes = os.path.join(package, "scenes")
        shutil.rmtree(scenes, ignore_errors=True)
        shutil.copytree(
            os.path.join(ROOT, "mitsuba_scenes"),
            scenes,
            ignore=shutil.ignore_patterns("__pycache__", "*.pyc", "make_assets.py"),
        )
        slices = os.path.join(package, "truth_slices")
        shutil.rmtree(slices, ignore_errors=True)
        os.makedirs(slices)
        for pattern in SLICES:
            for png in glob.glob(os.path.join(ROOT, "docs", "microgeometry", pattern)):
                shutil.copy2(png, slices)
        # build_py adds to what an earlier build left in build/lib, so files of a layout since
        # changed (a release no longer built) would ship: start the package there afresh.
        shutil.rmtree(os.path.join(self.build_lib, "matte_mitsuba"), ignore_errors=True)
        super().run()


class BinaryDistribution(Distribution):
    """Native code inside: installed to platlib (`Root-Is-Purelib: false`), as auditwheel and
    the package indexes require of a wheel with shared libraries."""

    def has_ext_modules(self):
        return True


class PlatformWheel(bdist_wheel):
    def get_tag(self):
        _, _, platform = super().get_tag()
        return "py3", "none", platform


setup(distclass=BinaryDistribution, cmdclass={"build_py": BuildPlugins, "bdist_wheel": PlatformWheel})
