"""The matte-mitsuba package as users install it: the release files of `make dist` (the sdist
holds what builds, with the package data, and nothing else; the wheel is platlib, repaired to a
manylinux tag with no library grafted in but Mitsuba's, which it loads from the mitsuba/drjit
wheels); the repaired wheel installed with `pip install --no-index --find-links dist` (Mitsuba
and flip-evaluator from the registry) in a fresh virtual environment outside the checkout, every command run with
the checkout hidden behind an empty mount (tests/plugin/wheel_checks.py: renders in llvm_ad_rgb
and scalar_rgb, roughdiffuse = oren_nayar with σ = α/√2, the mitsuba tool, the matte tool, the
packaged ground-truth tables; then `matte validate`, `validate --all`, `study` (with its HDR-FLIP values), `bench` and the
plugin benchmark); import before or after `mi.set_variant`. The wheel holds the kernels once
and a layer per supported Mitsuba release; each release is checked in test_releases.py."""

import glob
import io
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tarfile
import zipfile

import pytest
from conftest import CHECKOUT_MITSUBA, REPO, releases
from matte_mitsuba.all_types_scene import NAME as ALL_TYPES


def run_python(code, env=None, cwd=None):
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=cwd)


def test_import_before_set_variant_registers_every_variant(tmp_path):
    r = run_python(
        "import matte_mitsuba, mitsuba as mi\n"
        "for v in ('scalar_rgb', 'llvm_ad_rgb', 'llvm_ad_spectral'):\n"
        "    mi.set_variant(v); mi.load_dict({'type': 'roughdiffuse'})\n"
        "print('ok')",
        cwd=tmp_path,
    )
    assert r.stdout.strip() == "ok", r.stderr


# The platforms `make dist` builds a wheel for: this machine's (x86_64) and Linux aarch64
# (cross-built; run under emulation in test_aarch64.py), with the column of
# cpp/mitsuba_releases.txt that says which releases have a layer there.
ARCHES = {"x86_64": "linux-x86_64", "aarch64": "linux-aarch64"}


def release_wheel(arch="x86_64"):
    wheels = glob.glob(os.path.join(REPO, "dist", f"matte_mitsuba-*manylinux*_{arch}.whl"))
    assert len(wheels) == 1, f"make dist makes one manylinux wheel for {arch}: {wheels}"
    return wheels[0]


def test_sdist_holds_what_builds_and_nothing_else():
    sdists = glob.glob(os.path.join(REPO, "dist", "matte_mitsuba-*.tar.gz"))
    assert len(sdists) == 1, sdists
    with tarfile.open(sdists[0]) as t:
        names = [n.split("/", 1)[1] for n in t.getnames() if "/" in n]
    files = set(names)
    for needed in (
        "Cargo.toml",
        "Cargo.lock",
        "build.rs",
        "setup.py",
        "pyproject.toml",
        "README.md",
        "LICENSE",
        "cpp/build_plugin.py",
        ".cargo/config.toml",
        "cpp/plugin.cpp",
        "rust/matte/src/lib.rs",
        "rust/matte/src/main.rs",
        "python/matte_mitsuba/__init__.py",
        "python/matte_mitsuba/passes.py",
        "PKG-INFO",
    ):
        assert needed in files, f"{needed} missing from the sdist"
    # Every Rust and C++ source of the checkout is in it, the package with its tables, and the
    # package data the build copies in (the bundled scenes, the study report's slices).
    tracked = subprocess.run(
        ["git", "ls-files", "rust", "cpp", "python/matte_mitsuba", "mitsuba_scenes"],
        capture_output=True,
        text=True,
        cwd=REPO,
    ).stdout.split()
    assert tracked and set(tracked) <= files, sorted(set(tracked) - files)[:10]
    slices = [n for n in names if n.startswith("docs/") and n.endswith(".png")]
    assert len(slices) == 6 and all(n.startswith("docs/microgeometry/") and n.endswith(".png") for n in slices), slices
    # Nothing else: no tests, validation scripts, other docs or images, build outputs or plugins.
    for n in names:
        top = n.split("/")[0]
        assert top in {
            "Cargo.toml",
            "Cargo.lock",
            "build.rs",
            "rustfmt.toml",
            "setup.py",
            "setup.cfg",
            "pyproject.toml",
            "README.md",
            "LICENSE",
            "MANIFEST.in",
            ".cargo",
            "PKG-INFO",
            "rust",
            "cpp",
            "benches",
            "python",
            "mitsuba_scenes",
            "docs",
            "matte_mitsuba.egg-info",
        }, n
        assert not n.endswith((".exr", ".so", ".a", ".o")), n
        assert not n.endswith(".png") or n.startswith(("docs/microgeometry/", "mitsuba_scenes/")), n
        assert not n.startswith("python/") or n.startswith("python/matte_mitsuba"), n
        assert not n.startswith(("python/matte_mitsuba/scenes/", "python/matte_mitsuba/bin/")), n


@pytest.mark.parametrize("arch", sorted(ARCHES))
def test_wheel_is_platlib_and_manylinux_with_only_mitsubas_libraries_outside(arch):
    wheel = release_wheel(arch)
    tag = os.path.basename(wheel)[:-4].split("-")[-1]
    assert tag.startswith("manylinux_2_") and tag.endswith("_" + arch), tag
    with zipfile.ZipFile(wheel) as z:
        meta = z.read(next(n for n in z.namelist() if n.endswith(".dist-info/WHEEL"))).decode()
        assert "Root-Is-Purelib: false" in meta, meta
        names = z.namelist()
    assert not any(".data/purelib/" in n for n in names)
    # auditwheel grafted no copy of Mitsuba's or Dr.Jit's libraries.
    assert not any(os.path.basename(n).startswith(("libmitsuba", "libdrjit", "libnanothread")) for n in names), names
    show = subprocess.run(
        [os.path.join(REPO, ".venv", "bin", "auditwheel"), "show", "--json", wheel], capture_output=True, text=True
    )
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

    system = {
        "libc.so.6",
        "libm.so.6",
        "libstdc++.so.6",
        "libgcc_s.so.1",
        "libpthread.so.0",
        "libdl.so.2",
        {"x86_64": "ld-linux-x86-64.so.2", "aarch64": "ld-linux-aarch64.so.1"}[arch],
        "librt.so.1",
    }
    provided = {
        "libmitsuba.so",
        "libdrjit-core.so",
        "libdrjit-extra.so",
        "libnanothread.so",
        "libmatte_bsdfs.so",
        "libmatte_kernels.so",
    }
    elves = 0
    with zipfile.ZipFile(wheel) as z:
        for n in z.namelist():
            data = z.read(n)
            if not data.startswith(b"\x7fELF"):
                continue
            elves += 1
            elf = ELFFile(io.BytesIO(data))
            assert elf["e_machine"] == {"x86_64": "EM_X86_64", "aarch64": "EM_AARCH64"}[arch], (n, elf["e_machine"])
            needed = {
                t.needed
                for sec in elf.iter_sections()
                if isinstance(sec, DynamicSection)
                for t in sec.iter_tags()
                if t.entry.d_tag == "DT_NEEDED"
            }
            assert needed <= system | provided, (n, needed - system - provided)
    # The kernels once; per supported release, its layer and one stub per registered type.
    published = releases(ARCHES[arch])
    types = subprocess.run([os.path.join(REPO, ".venv", "bin", "matte"), "types"], capture_output=True, text=True)
    expected = {"matte_mitsuba/lib/libmatte_kernels.so"} | {
        f"matte_mitsuba/releases/{r}/plugins/{name}.so"
        for r in published
        for name in ["libmatte_bsdfs", *types.stdout.split()]
    }
    assert {n for n in names if n.endswith(".so")} == expected, sorted(
        {n for n in names if n.endswith(".so")} ^ expected
    )
    assert elves == len(expected) + 1, elves  # and the matte tool


def hidden_checkout(cmd):
    """`cmd` run with the checkout hidden: an empty tmpfs mounted over it in a private mount
    namespace (`unshare -m` as root, `unshare -rm` otherwise). Anything the installation still
    read from the tree it was built in would be missing there."""
    mount = 'mount -t tmpfs none "$0" && exec "$@"'
    return ["unshare", "-m" if os.geteuid() == 0 else "-rm", "sh", "-c", mount, REPO, *cmd]


def can_hide_the_checkout():
    r = subprocess.run(hidden_checkout(["sh", "-c", 'test -z "$(ls -A "$1")"', "sh", REPO]), capture_output=True)
    return r.returncode == 0


# A scene of the user's, written by the test: three of matte's BSDFs and a Mitsuba built-in.
USER_SCENE = """<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="3"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
        <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="24"/></film>
    </sensor>
    <shape type="sphere"><point name="center" x="-0.9" y="0" z="0"/><float name="radius" value="0.6"/>
        <bsdf type="eon"><float name="roughness" value="0.6"/><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf></shape>
    <shape type="sphere"><point name="center" x="0.4" y="0" z="0"/><float name="radius" value="0.6"/>
        <bsdf type="ginneken"><float name="roughness" value="0.4"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="4"/><translate z="-1"/></transform>
        <bsdf type="wolff"/></shape>
    <emitter type="constant"><rgb name="radiance" value="0.8"/></emitter>
</scene>
"""


def test_the_installed_package_works_with_the_checkout_hidden(tmp_path):
    """The wheel in a fresh environment outside the checkout, every command run with the
    checkout hidden (`hidden_checkout`): the Mitsuba user's checks (tests/plugin/wheel_checks.py),
    `matte validate` on a scene of the user's, `matte validate --all --quick` (every bundled
    scene, an installation self-test), `matte study` on one bundled scene, `matte bench` (the
    matte side, on the bundled scenes) and the plugin benchmark on `tabulated_brdf`."""
    if not sys.platform.startswith("linux"):
        pytest.skip(
            "hides the checkout with a Linux mount namespace (unshare); the workflow's other jobs run the release checks"
        )
    if not can_hide_the_checkout():
        if os.geteuid() == 0:
            pytest.fail("unshare -m cannot mount over the checkout as root")
        pytest.skip("needs a mount namespace (unshare -rm) to hide the checkout")
    wheel = release_wheel()
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    py = str(venv / "bin" / "python")
    pip = [py, "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    # The pinned Mitsuba (and numpy, flip-evaluator) from the registry, then matte only from
    # the release files.
    r = subprocess.run(
        pip + [f"mitsuba=={CHECKOUT_MITSUBA}", "numpy", "flip-evaluator"], capture_output=True, text=True
    )
    assert r.returncode == 0, r.stderr
    r = subprocess.run(
        pip + ["--no-index", "--find-links", os.path.dirname(wheel), "matte-mitsuba"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    shown = subprocess.run([py, "-m", "pip", "show", "-f", "matte-mitsuba"], capture_output=True, text=True).stdout
    assert "Version: 0.1.0" in shown
    # The bundled scenes: mitsuba_scenes/ and the one the build writes from the registry.
    bundled = sorted([f for f in os.listdir(os.path.join(REPO, "mitsuba_scenes")) if f.endswith(".xml")] + [ALL_TYPES])
    checks = tmp_path / "wheel_checks.py"
    shutil.copy(os.path.join(REPO, "tests", "plugin", "wheel_checks.py"), checks)
    work = tmp_path / "work"
    work.mkdir()
    (work / "my_scene.xml").write_text(USER_SCENE)
    matte = str(venv / "bin" / "matte")

    def run(*cmd, timeout=900):
        return subprocess.run(
            hidden_checkout(list(cmd)),
            capture_output=True,
            text=True,
            cwd=work,
            timeout=timeout,
            env={k: v for k, v in os.environ.items() if not k.startswith(("MATTE", "VIRTUAL_ENV"))},
        )

    check = run(py, str(checks))
    print(check.stdout)
    assert check.returncode == 0, check.stdout + check.stderr
    assert check.stdout.count("\nok") + check.stdout.startswith("ok") == 8, check.stdout

    # A scene of the user's, by its file name in the working folder.
    r = run(matte, "validate", "my_scene.xml", "--quick", "-o", "one")
    assert r.returncode == 0 and "PASS my_scene.xml vs llvm_ad_rgb" in r.stderr, r.stdout + r.stderr
    assert (work / "one" / "report.html").is_file()
    summary = json.loads((work / "one" / "summary.json").read_text())
    provenance = summary["provenance"]
    assert summary["passed"] and provenance["mitsuba"] == CHECKOUT_MITSUBA, provenance
    assert provenance["python"].startswith(py) and "1 given on the command line" == provenance["scenes"], provenance
    report = (work / "one" / "report.html").read_text()
    assert "Mitsuba" in report and CHECKOUT_MITSUBA in report and "mitsuba llvm_ad_rgb" in report

    # Every bundled scene: the installation's self-test.
    r = run(matte, "validate", "--all", "--quick", "-o", "all")
    assert r.returncode == 0, r.stdout + r.stderr
    assert f"all {len(bundled)} comparison(s) passed" in r.stdout, r.stdout + r.stderr
    summary = json.loads((work / "all" / "summary.json").read_text())
    assert sorted(os.path.basename(s["scene"]) for s in summary["scenes"]) == bundled
    assert all(s["scene"].startswith(str(venv)) for s in summary["scenes"]), summary["scenes"][0]["scene"]
    assert summary["provenance"]["scenes"].startswith(f"{len(bundled)} bundled with matte_mitsuba ("), summary[
        "provenance"
    ]

    # The paper's study on one bundled scene, by name, with the true surfaces from the package.
    r = run(
        matte,
        "study",
        "cornell",
        "--res",
        "16",
        "--spp",
        "4",
        "--passes",
        "2",
        "--no-variants",
        "--no-convergence",
        "-q",
        "-o",
        "study",
    )
    assert r.returncode == 0, r.stdout + r.stderr
    study = json.loads((work / "study" / "study.json").read_text())
    keys = [m["key"] for m in study["scenes"][0]["models"]]
    assert "truth_v_cavities" in keys and "truth_height_field" in keys, keys
    html = (work / "study" / "report.html").read_text()
    for part in html.split('src="')[1:]:
        assert (work / "study" / part.split('"')[0]).is_file(), part.split('"')[0]
    assert "truth_slices/truth_slice_eon.png" in html
    # The perceptual differences, computed by the installed package's flip-evaluator.
    perceptual = study["perceptual"]
    assert perceptual["notes"] == [] and len(perceptual["scenes"]) == 1, perceptual["notes"]
    assert all(math.isfinite(c["mean"]) for c in perceptual["scenes"][0]["comparisons"])
    assert "cornell/flip_lambert_global.png" in html

    # The benchmarks: matte's side on the bundled scenes, and the plugin benchmark on one type.
    r = run(matte, "bench", "--quick", "--no-mitsuba", "-q", "-o", "bench")
    assert r.returncode == 0 and (work / "bench" / "bench.json").is_file(), r.stdout + r.stderr
    r = run(
        py,
        "-m",
        "matte_mitsuba.bench_plugin",
        "--types",
        "tabulated_brdf",
        "--res",
        "16",
        "--spp",
        "1",
        "--repeats",
        "1",
    )
    assert r.returncode == 0, r.stdout + r.stderr
    assert re.search(r"tabulated_brdf\s+[0-9.]+ s\s+[0-9.]+x diffuse", r.stdout), r.stdout
