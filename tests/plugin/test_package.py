"""The matte-mitsuba package as users install it: the wheel `make plugin` built, in a fresh
virtual environment outside the checkout (validation/check_wheel.py: renders in llvm_ad_rgb
and scalar_rgb, roughdiffuse = oren_nayar with σ = α/√2, the mitsuba tool, the matte tool);
import before or after `mi.set_variant`; a Mitsuba other than the one it was built against is
refused at import naming both versions."""
import glob
import os
import shutil
import subprocess
import sys

import pytest

from conftest import REPO


def run_python(code, env=None, cwd=None):
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=cwd)


def test_import_before_set_variant_registers_every_variant(tmp_path):
    r = run_python("import matte_mitsuba, mitsuba as mi\n"
                   "for v in ('scalar_rgb', 'llvm_ad_rgb', 'llvm_ad_spectral'):\n"
                   "    mi.set_variant(v); mi.load_dict({'type': 'roughdiffuse'})\n"
                   "print('ok')", cwd=tmp_path)
    assert r.stdout.strip() == "ok", r.stderr


def test_other_mitsuba_version_is_refused_naming_both(tmp_path):
    import matte_mitsuba
    copy = tmp_path / "matte_mitsuba"
    shutil.copytree(matte_mitsuba.PLUGIN_ROOT, copy, ignore=shutil.ignore_patterns("bin", "__pycache__"))
    (copy / "_build.py").write_text('MITSUBA_VERSION = "3.8.0"\n')
    env = {**os.environ, "PYTHONPATH": str(tmp_path)}
    r = run_python("import matte_mitsuba", env=env, cwd=tmp_path)
    assert r.returncode != 0
    last = r.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError") and "3.8.0" in last and "3.9.1" in last, r.stderr


def test_wheel_in_a_fresh_environment_outside_the_checkout(tmp_path):
    wheels = glob.glob(os.path.join(REPO, "dist", "matte_mitsuba-*.whl"))
    assert len(wheels) == 1, wheels
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    py = str(venv / "bin" / "python")
    pip = subprocess.run([py, "-m", "pip", "install", "-q", "--disable-pip-version-check", wheels[0]], capture_output=True, text=True)
    assert pip.returncode == 0, pip.stderr
    check = subprocess.run([py, os.path.join(REPO, "validation", "check_wheel.py")], capture_output=True, text=True, cwd=tmp_path)
    print(check.stdout)
    assert check.returncode == 0, check.stdout + check.stderr
    assert check.stdout.count("\nok") + check.stdout.startswith("ok") == 7, check.stdout
