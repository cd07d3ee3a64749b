"""The wheel's build step (pyproject.toml has the metadata): build the plugins and the `matte`
binary with cpp/build_plugin.sh against the Mitsuba of the building Python, put the binary and
the ground-truth tables (validation/ground_truth/*.json) into the package, and tag the wheel for this platform (it holds native code, but no Python
extension: any Python 3 that runs Mitsuba can load it)."""
import os
import shutil
import subprocess
import sys

from setuptools import setup
from setuptools.command.bdist_wheel import bdist_wheel
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

ROOT = os.path.dirname(os.path.abspath(__file__))


class BuildPlugins(build_py):
    def run(self):
        subprocess.check_call([os.path.join(ROOT, "cpp", "build_plugin.sh")], env={**os.environ, "MATTE_PYTHON": sys.executable})
        binary = os.path.join(ROOT, "python", "matte_mitsuba", "bin", "matte")
        os.makedirs(os.path.dirname(binary), exist_ok=True)
        shutil.copy2(os.path.join(ROOT, "target", "release", "matte"), binary)
        subprocess.check_call(["strip", binary])
        tables = os.path.join(ROOT, "python", "matte_mitsuba", "ground_truth")
        shutil.rmtree(tables, ignore_errors=True)
        shutil.copytree(os.path.join(ROOT, "validation", "ground_truth"), tables,
                        ignore=lambda folder, names: [n for n in names if not n.endswith(".json")])
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
