"""The matte-mitsuba package as users install it: the release files of `make dist` (the sdist
holds what builds and nothing else; the wheel is platlib, repaired to a manylinux tag with no
library grafted in but Mitsuba's, which it loads from the mitsuba/drjit wheels); the repaired
wheel installed with `pip install --no-index --find-links dist` (Mitsuba from the registry) in a
fresh virtual environment outside the checkout (validation/check_wheel.py: renders in llvm_ad_rgb
and scalar_rgb, roughdiffuse = oren_nayar with σ = α/√2, the mitsuba tool, the matte tool, the
packaged ground-truth tables);
import before or after `mi.set_variant`; a Mitsuba other than the one it was built against is
refused at import naming both versions."""
import glob
import io
import json
import os
import shutil
import subprocess
import sys
import tarfile
import zipfile

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


def release_wheel():
    wheels = glob.glob(os.path.join(REPO, "dist", "matte_mitsuba-*manylinux*.whl"))
    assert len(wheels) == 1, f"make dist makes one manylinux wheel: {wheels}"
    return wheels[0]


def test_sdist_holds_what_builds_and_nothing_else():
    sdists = glob.glob(os.path.join(REPO, "dist", "matte_mitsuba-*.tar.gz"))
    assert len(sdists) == 1, sdists
    with tarfile.open(sdists[0]) as t:
        names = [n.split("/", 1)[1] for n in t.getnames() if "/" in n]
    files = set(names)
    for needed in ("Cargo.toml", "Cargo.lock", "build.rs", "setup.py", "pyproject.toml", "README.md", "LICENSE",
                   "cpp/build_plugin.sh", "cpp/plugin.cpp", "rust/lib.rs", "rust/main.rs",
                   "python/matte_mitsuba/__init__.py", "PKG-INFO"):
        assert needed in files, f"{needed} missing from the sdist"
    # Every Rust and C++ source of the checkout is in it.
    # So is every ground-truth table (the wheel ships them).
    tracked = subprocess.run(["git", "ls-files", "rust", "cpp", "validation/ground_truth"], capture_output=True, text=True,
                             cwd=REPO).stdout.split()
    assert tracked and set(tracked) <= files, sorted(set(tracked) - files)[:10]
    # Nothing else: no tests, scenes, docs, images, build outputs or compiled plugins.
    for n in names:
        top = n.split("/")[0]
        assert top in {"Cargo.toml", "Cargo.lock", "build.rs", "rustfmt.toml", "setup.py", "setup.cfg", "pyproject.toml",
                       "README.md", "LICENSE", "MANIFEST.in", "PKG-INFO", "rust", "cpp", "benches", "python",
                       "matte_mitsuba.egg-info"} or n in ("validation", "validation/ground_truth") \
            or (n.startswith("validation/ground_truth/") and n.endswith(".json")), n
        assert not n.endswith((".png", ".exr", ".so", ".a", ".o")), n
        assert not n.startswith("python/") or n.startswith("python/matte_mitsuba"), n


def test_wheel_is_platlib_and_manylinux_with_only_mitsubas_libraries_outside():
    wheel = release_wheel()
    tag = os.path.basename(wheel)[:-4].split("-")[-1]
    assert tag.startswith("manylinux_2_") and tag.endswith("_x86_64"), tag
    with zipfile.ZipFile(wheel) as z:
        meta = z.read(next(n for n in z.namelist() if n.endswith(".dist-info/WHEEL"))).decode()
        assert "Root-Is-Purelib: false" in meta, meta
        names = z.namelist()
    assert not any(".data/purelib/" in n for n in names)
    # auditwheel grafted no copy of Mitsuba's or Dr.Jit's libraries.
    assert not any(os.path.basename(n).startswith(("libmitsuba", "libdrjit", "libnanothread")) for n in names), names
    show = subprocess.run([os.path.join(REPO, ".venv", "bin", "auditwheel"), "show", "--json", wheel],
                          capture_output=True, text=True)
    assert show.returncode == 0, show.stderr
    report = json.loads(show.stdout)
    # The symbol versions allow exactly this tag (the lowest one they allow), no ISA beyond the
    # policy's, and the only external libraries are ones the mitsuba/drjit wheels provide
    # (which keep auditwheel's overall verdict at linux_x86_64: they are not system libraries).
    assert report["sym_tag"] == tag and not report["unsupported_isa"], report
    external = set(report["external_libs"])
    assert "libmitsuba.so" in external, external
    assert external <= {"libmitsuba.so", "libdrjit-core.so", "libdrjit-extra.so", "libnanothread.so"}, external
    # Every ELF file in the wheel needs only the policy's system libraries, Mitsuba's and
    # Dr.Jit's (loaded from their wheels, excluded from grafting) and matte's own library.
    from elftools.elf.dynamic import DynamicSection
    from elftools.elf.elffile import ELFFile
    system = {"libc.so.6", "libm.so.6", "libstdc++.so.6", "libgcc_s.so.1", "libpthread.so.0", "libdl.so.2",
              "ld-linux-x86-64.so.2", "librt.so.1"}
    provided = {"libmitsuba.so", "libdrjit-core.so", "libdrjit-extra.so", "libnanothread.so", "libmatte_bsdfs.so"}
    elves = 0
    with zipfile.ZipFile(wheel) as z:
        for n in z.namelist():
            data = z.read(n)
            if not data.startswith(b"\x7fELF"):
                continue
            elves += 1
            elf = ELFFile(io.BytesIO(data))
            needed = {t.needed for sec in elf.iter_sections() if isinstance(sec, DynamicSection)
                      for t in sec.iter_tags() if t.entry.d_tag == "DT_NEEDED"}
            assert needed <= system | provided, (n, needed - system - provided)
    assert elves >= 8, elves  # the library, one stub per model, the matte tool


def test_wheel_in_a_fresh_environment_outside_the_checkout(tmp_path):
    wheel = release_wheel()
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    py = str(venv / "bin" / "python")
    pip = [py, "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    # The pinned Mitsuba from the registry, then matte only from the release files.
    r = subprocess.run(pip + ["mitsuba==3.9.1"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    r = subprocess.run(pip + ["--no-index", "--find-links", os.path.dirname(wheel), "matte-mitsuba"],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    shown = subprocess.run([py, "-m", "pip", "show", "-f", "matte-mitsuba"], capture_output=True, text=True).stdout
    assert "Version: 0.1.0" in shown
    check = subprocess.run([py, os.path.join(REPO, "validation", "check_wheel.py")], capture_output=True, text=True, cwd=tmp_path)
    print(check.stdout)
    assert check.returncode == 0, check.stdout + check.stderr
    assert check.stdout.count("\nok") + check.stdout.startswith("ok") == 8, check.stdout
