#!/usr/bin/env python3
"""Builds matte's Mitsuba plugin for one platform, for every Mitsuba release of
cpp/mitsuba_releases.txt published there (and the installed one, when the table lacks it):

 1. once: the Rust staticlib (the matte-plugin crate: kernels + cxx bridge glue) and the `matte`
    binary, for the platform's Rust target;
 2. per release: its headers and libraries (mitsuba/include, libmitsuba, drjit/include and
    Dr.Jit's libraries), taken from that release's mitsuba and drjit wheels for the platform,
    downloaded from the package index by pip and cached in $MATTE_MITSUBA_CACHE (default
    ~/.cache/matte-mitsuba), or from the installed Mitsuba for a release the table lacks;
 3. per release: cpp/plugin.cpp compiled against them with that release's instruction set,
    C++ string ABI and backends (the release's C++ layer), in parallel;
 4. once: lib/<kernels library>, the Rust kernels with the bridge symbols the layers call, so
    the kernels ship once;
 5. per release: releases/<release>/plugins/<layer library> (linked against the kernels and the
    release's Mitsuba and Dr.Jit libraries, with an unresolved symbol an error: the link check)
    and one small stub <type><suffix> per plugin name (exports only init_plugin, forwards to the
    layer);
 6. bin/matte (stripped) and _build.py: the platform, the releases built and the model registry.

    python3 cpp/build_plugin.py [--platform NAME] [--out DIR]

Platforms (PLATFORMS below; one column each in cpp/mitsuba_releases.txt):

  linux-x86_64   g++ (ELF: -z defs, a version script, $ORIGIN rpaths)
  linux-aarch64  g++; cross-built on x86-64 with Debian's g++-aarch64-linux-gnu and Rust's
                 aarch64-unknown-linux-gnu target
  macos-arm64    clang++ on a Mac; cross-built on Linux with Zig (PyPI's ziglang, as the C++
                 compiler and Mach-O linker, and cargo-zigbuild for Rust's aarch64-apple-darwin):
                 Mach-O, undefined symbols an error, @rpath install names, @loader_path rpaths,
                 libc++ imported from /usr/lib/libc++.1.dylib as Mitsuba's own libraries do
  windows-x86_64 MSVC (cl, link, lib) on Windows only (no cross build: MSVC's C++ ABI); the
                 import libraries of Mitsuba's DLLs are made from their export tables, an
                 unresolved external fails link; the kernels are linked into each layer

The platform defaults to this machine's. DIR defaults to python/matte_mitsuba.
MATTE_MITSUBA_RELEASES="3.9.1 3.8.0" builds a subset of the table (a development shortcut; a
wheel for users holds every release). The installed Mitsuba is the one of $MATTE_MITSUBA_PYTHON,
else of the Python running this script (outside pip's build isolation); a release of it that
the table lacks gets a layer from its own headers. setup.py calls this for the wheel, and `make
plugin`/`make dist` through it.
"""

import argparse
import concurrent.futures
import importlib.util
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import zipfile
from dataclasses import dataclass

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TABLE = os.path.join(ROOT, "cpp", "mitsuba_releases.txt")


@dataclass(frozen=True)
class Platform:
    """What building for one platform takes."""

    name: str  # the table's column and the CLI's name
    os: str  # "linux", "macos" or "windows": the binary format, its link check and toolchain
    machine: str  # platform.machine() where it runs natively, lower case
    rust_target: str
    wheel_platforms: tuple  # pip --platform tags that find Mitsuba's wheels
    wheel_tag: str  # the tag of matte's own wheel (before any repair)
    # Compiler flags per instruction set of the table's column.
    isa_flags: dict
    # How it is cross-built on Linux: a GNU toolchain's prefix (g++, nm, strip), "zig", or None
    # (not cross-buildable), and what provides that toolchain.
    cross: str | None
    cross_packages: str

    def library(self, name):
        """The file name of shared library `name` (libNAME.so, libNAME.dylib, NAME.dll)."""
        return {"linux": f"lib{name}.so", "macos": f"lib{name}.dylib", "windows": f"{name}.dll"}[self.os]

    @property
    def plugin_suffix(self):
        """What Mitsuba appends to a plugin's name (src/core/plugin.cpp: .so, .dylib, .dll)."""
        return {"linux": ".so", "macos": ".dylib", "windows": ".dll"}[self.os]

    def executable(self, name):
        return name + ".exe" if self.os == "windows" else name


PLATFORMS = {
    p.name: p
    for p in (
        Platform(
            "linux-x86_64",
            "linux",
            "x86_64",
            "x86_64-unknown-linux-gnu",
            ("manylinux_2_28_x86_64", "manylinux_2_17_x86_64", "manylinux2014_x86_64"),
            "linux_x86_64",
            {"avx": ["-mavx"], "x86-64-v3": ["-march=x86-64-v3"]},
            "x86_64-linux-gnu-",
            "Debian: apt-get install g++-x86-64-linux-gnu",
        ),
        Platform(
            "linux-aarch64",
            "linux",
            "aarch64",
            "aarch64-unknown-linux-gnu",
            ("manylinux_2_28_aarch64", "manylinux_2_17_aarch64", "manylinux2014_aarch64"),
            "linux_aarch64",
            {"armv8-a": ["-march=armv8-a"]},
            "aarch64-linux-gnu-",
            "Debian: apt-get install g++-aarch64-linux-gnu",
        ),
        Platform(
            "macos-arm64",
            "macos",
            "arm64",
            "aarch64-apple-darwin",
            ("macosx_11_0_arm64",),
            "macosx_11_0_arm64",
            {"arm64": []},  # the compilers' arm64 baseline, as Mitsuba's macOS wheels
            "zig",
            "pip install ziglang cargo-zigbuild lief",
        ),
        Platform(
            "windows-x86_64",
            "windows",
            "amd64",
            "x86_64-pc-windows-msvc",
            ("win_amd64",),
            "win_amd64",
            {"avx": ["/arch:AVX"], "x86-64-v3": ["/arch:AVX2"]},
            None,
            "MSVC's C++ ABI: build it on Windows with Visual Studio's tools (cl, link, lib)",
        ),
    )
}
# The libraries each layer links against, from the mitsuba and drjit wheels (not shipped).
MITSUBA_LIBRARIES = ["mitsuba", "drjit-core", "drjit-extra", "nanothread"]
# The deployment target of the macOS layers: Mitsuba's macOS wheels' (macosx_11_0_arm64).
MACOS_MIN = "11.0"
# libc++ symbols matte's objects import (cxx's runtime: its Str throws std::invalid_argument; its
# shared_ptr bridge locks a weak count) that no Mach-O file of Mitsuba's wheels imports: each is
# in libc++'s stable ABI v1 of every macOS (<stdexcept>, <memory>). The macOS link check accepts
# libc++ imports that Mitsuba's own binaries make and these; any other fails the link, naming it.
LIBCXX_ALSO = ["__ZNSt16invalid_argumentD1Ev", "__ZTVSt16invalid_argument", "__ZNSt3__119__shared_weak_count4lockEv"]


class BuildError(Exception):
    pass


def host_platform():
    machine = platform.machine().lower()
    system = {"linux": "linux", "darwin": "macos", "win32": "windows"}.get(sys.platform)
    for p in PLATFORMS.values():
        if p.os == system and p.machine == machine:
            return p
    raise BuildError(f"no platform of cpp/build_plugin.py is this machine ({sys.platform} {machine})")


def read_table():
    """[(release, drjit, {platform: isa or None})] from cpp/mitsuba_releases.txt."""
    names = list(PLATFORMS)
    rows = []
    for n, line in enumerate(open(TABLE), 1):
        if not line.strip() or line.startswith("#"):
            continue
        cols = line.split()
        if len(cols) != 2 + len(names):
            raise BuildError(f"{TABLE}:{n}: expected {2 + len(names)} columns (release, drjit, {', '.join(names)})")
        rows.append((cols[0], cols[1], {p: (None if c == "-" else c) for p, c in zip(names, cols[2:])}))
    return rows


def run(cmd, **kw):
    r = subprocess.run(cmd, **kw)
    if r.returncode != 0:
        raise BuildError(f"failed ({r.returncode}): {' '.join(map(str, cmd))}")
    return r


def output(cmd, **kw):
    return run(cmd, capture_output=True, text=True, **kw).stdout


def installed_mitsuba(python=None):
    """The installed Mitsuba (version, Dr.Jit version, package folders), or None: that of
    $MATTE_MITSUBA_PYTHON, else of `python`. Asked in isolated mode (-I), outside pip's build
    isolation, which hides the environment's packages from the build."""
    python = os.environ.get("MATTE_MITSUBA_PYTHON") or python or sys.executable
    code = (
        "import json, os, importlib.util as u\n"
        "from importlib.metadata import version\n"
        "s, d = u.find_spec('mitsuba'), u.find_spec('drjit')\n"
        "print(json.dumps(None if s is None or d is None else [version('mitsuba'), version('drjit'),"
        " os.path.dirname(s.origin), os.path.dirname(d.origin)]))\n"
    )
    r = subprocess.run([python, "-I", "-c", code], capture_output=True, text=True)
    if r.returncode != 0 or not r.stdout.strip():
        return None
    found = json.loads(r.stdout.strip().splitlines()[-1])
    return tuple(found) if found else None


def detect_isa(target, mitsuba_dir):
    """The instruction set an installed Mitsuba was compiled for. On x86-64 it is read from its
    library (x86-64-v3 when it holds FMA instructions, else avx; objdump reads ELF and PE); a
    platform with one instruction set in the table has that one."""
    isas = list(target.isa_flags)
    if len(isas) == 1:
        return isas[0]
    lib = os.path.join(mitsuba_dir, target.library("mitsuba"))
    objdump = subprocess.Popen(["objdump", "-d", "--no-show-raw-insn", lib], stdout=subprocess.PIPE, text=True)
    fma = any(op in line for line in objdump.stdout for op in ("vfmadd", "vfmsub", "vfnmadd"))
    objdump.kill()
    objdump.wait()
    return "x86-64-v3" if fma else "avx"


def release_key(version):
    return tuple(int(x) if x.isdigit() else 0 for x in version.split("."))


def plan(target):
    """The layers to build for `target`: [(release, drjit, isa, installed)], oldest first: the
    table's releases published for the platform (or the subset MATTE_MITSUBA_RELEASES names),
    and the installed Mitsuba's release when the table lacks it (installed: its folders)."""
    rows = read_table()
    subset = os.environ.get("MATTE_MITSUBA_RELEASES", "").replace(",", " ").split()
    unknown = [r for r in subset if r not in [row[0] for row in rows]]
    if unknown:
        raise BuildError(f"MATTE_MITSUBA_RELEASES names {', '.join(unknown)}, not in cpp/mitsuba_releases.txt")
    out = []
    for version, drjit, isas in rows:
        isa = isas[target.name]
        if isa is None or (subset and version not in subset):
            continue
        if isa not in target.isa_flags:
            raise BuildError(f"{TABLE}: unknown instruction set {isa!r} for {version} on {target.name}")
        out.append((version, drjit, isa, None))
    found = None if is_cross(target) else installed_mitsuba()
    if found and found[0] not in [row[0] for row in rows]:
        if release_key(found[0]) < release_key(rows[0][0]):
            print(
                f"build_plugin: the installed Mitsuba {found[0]} predates the plugin API of {rows[0][0]}, "
                "the oldest release matte supports: no layer for it",
                file=sys.stderr,
            )
        else:
            out.append((found[0], found[1], None, found))
    if not out:
        raise BuildError(f"no Mitsuba release to build for {target.name}")
    return sorted(out, key=lambda r: release_key(r[0]))


def requirement(target):
    """The wheel's Mitsuba requirement: the releases it has layers for."""
    versions = [r[0] for r in plan(target)]
    return f"mitsuba>={versions[0]},<={versions[-1]}"


@dataclass
class Release:
    """One layer to build: the release, its headers and libraries, its instruction set."""

    version: str
    mitsuba_dir: str  # holds include/ and Mitsuba's library
    drjit_dir: str  # holds include/ and Dr.Jit's libraries
    isa: str
    source: str  # where its headers came from, for the summary
    root: str | None  # the cache folder of a downloaded release (macOS: its libc++ stub)


# The Rust half of a layer: the kernels' static library and the `matte` command, in release.
# (The Makefile's rust-release target runs the same command for this machine ahead of the wheel.)
RUST_BUILD = ["cargo", "build", "--release", "--quiet", "-p", "matte-plugin", "-p", "matte"]


class Build:
    def __init__(self, target, out):
        self.target = target
        self.cross = is_cross(target)
        self.out = out
        self.cache = os.environ.get("MATTE_MITSUBA_CACHE") or os.path.join(
            os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "matte-mitsuba"
        )
        self.cargo_target = os.environ.get("CARGO_TARGET_DIR") or os.path.join(ROOT, "target")
        self.obj = os.path.join(self.cargo_target, "plugin", target.name)
        self.python = sys.executable
        self.zig = self.cross and target.cross == "zig"
        if self.cross and target.cross is None:
            raise BuildError(f"{target.name} cannot be cross-built here: {target.cross_packages}")
        if self.zig:
            missing = [m for m in ("ziglang", "lief") if importlib.util.find_spec(m) is None]
            if missing or not shutil.which("cargo-zigbuild", path=self.tool_path()):
                raise BuildError(
                    f"cross-building for {target.name} needs Zig, cargo-zigbuild and lief ({target.cross_packages})"
                )
        self.cxx = self.compiler()

    def tool_path(self):
        """PATH with this Python's scripts first (cargo-zigbuild, which runs `python -m ziglang`)."""
        return os.pathsep.join([os.path.dirname(self.python), os.environ.get("PATH", "")])

    def tool(self, name):
        """The toolchain's `name` (g++, gcc, ar, nm, strip) for the target: the cross one when
        cross-building with a GNU toolchain."""
        if not self.cross:
            return name
        path = shutil.which(self.target.cross + name)
        if not path:
            raise BuildError(
                f"cross-building for {self.target.name} needs {self.target.cross}{name} ({self.target.cross_packages})"
            )
        return path

    def compiler(self):
        """The C++ compiler (and linker driver) as a command prefix."""
        if self.target.os == "windows":
            return ["cl", "/nologo"]
        if self.zig:
            # Zig's clang with its libc++ headers, told that the library is Apple's (availability
            # markup for the deployment target, as Apple's SDK does), so that nothing newer than
            # macOS 11's /usr/lib/libc++.1.dylib is called.
            return [self.python, "-m", "ziglang", "c++", "-target", f"aarch64-macos.{MACOS_MIN}"] + [
                "-U_LIBCPP_HAS_VENDOR_AVAILABILITY_ANNOTATIONS",
                "-D_LIBCPP_HAS_VENDOR_AVAILABILITY_ANNOTATIONS=1",
            ]
        if self.target.os == "macos":
            return ["clang++", "-arch", "arm64", f"-mmacosx-version-min={MACOS_MIN}"]
        return [self.tool("g++")]

    # 1. Rust.
    def rust_dir(self):
        """Where cargo puts the target's release artifacts."""
        if self.cross:
            return os.path.join(self.cargo_target, self.target.rust_target, "release")
        return os.path.join(self.cargo_target, "release")

    def staticlib(self):
        name = "matte_plugin.lib" if self.target.os == "windows" else "libmatte_plugin.a"
        return os.path.join(self.rust_dir(), name)

    def build_rust(self):
        cmd = list(RUST_BUILD)
        # Not make's jobserver (make test runs this beside other jobs, without passing it on).
        native = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "CARGO_MAKEFLAGS")}
        env = dict(native)
        if self.target.os == "macos":
            env["MACOSX_DEPLOYMENT_TARGET"] = MACOS_MIN
        if self.cross:
            installed = output(["rustup", "target", "list", "--installed"]) if shutil.which("rustup") else ""
            if self.target.rust_target not in installed.split():
                raise BuildError(
                    f"cross-building for {self.target.name} needs Rust's {self.target.rust_target} target "
                    f"(rustup target add {self.target.rust_target})"
                )
            if self.zig:
                # cargo-zigbuild: Zig as the C/C++ compiler of the cxx bridge and as the linker
                # of the `matte` binary (Zig carries macOS's libSystem stubs; no SDK needed).
                cmd[1] = "zigbuild"
                env["PATH"] = self.tool_path()
            else:
                # The cxx bridge's C++ (cc) for the target, with the target's compiler.
                triple = self.target.rust_target.replace("-", "_")
                env.setdefault("CXX_" + triple, self.cxx[0])
                env.setdefault("CC_" + triple, self.tool("gcc"))
                env.setdefault("AR_" + triple, self.tool("ar"))
            cmd += ["--target", self.target.rust_target]
        # cc (in build.rs) asks the compiler for `--version`; Zig's c++ answers with an empty
        # a.o in the folder it runs in, the build script's: the checkout. Not left behind.
        stray = os.path.join(ROOT, "a.o")
        stray_before = os.path.exists(stray)
        run(cmd, cwd=ROOT, env=env)
        if self.zig and not stray_before and os.path.isfile(stray) and os.path.getsize(stray) == 0:
            os.remove(stray)
        if self.cross:
            # The type list and the registry come from a matte that runs here: the native build's
            # (the same packages, so the same features: nothing to build after a native build).
            run(RUST_BUILD, cwd=ROOT, env=native)
        # The generated bridge header includes "matte/cpp/arena.h" (build.rs sets the prefix `matte`).
        inc = os.path.join(self.cargo_target, "inc")
        os.makedirs(inc, exist_ok=True)
        link = os.path.join(inc, "matte")
        if os.path.realpath(link) != ROOT:
            if os.path.lexists(link) or os.path.isdir(link):
                shutil.rmtree(link) if os.path.isdir(link) and not os.path.islink(link) else os.remove(link)
            try:
                os.symlink(ROOT, link, target_is_directory=True)
            except OSError:  # Windows without the right to make links: a copy of what is included
                shutil.copytree(os.path.join(ROOT, "cpp"), os.path.join(link, "cpp"))

    def host_matte(self, *args):
        return output([os.path.join(self.cargo_target, "release", host_platform().executable("matte")), *args])

    # 2. Headers and libraries.
    def wanted(self, name):
        """Whether a file of a Mitsuba or Dr.Jit wheel is one a layer builds or links against:
        the headers, and the shared libraries (and Windows' import libraries) beside __init__.py."""
        package, _, rest = name.partition("/")
        if rest.startswith("include/"):
            return True
        if "/" in rest or not rest:
            return False
        if self.target.os == "windows":
            return rest.endswith((".dll", ".lib"))
        return rest.startswith("lib") and (".so" in rest if self.target.os == "linux" else rest.endswith(".dylib"))

    def fetch(self, version, drjit, isa):
        dest = os.path.join(self.cache, self.target.name, version)
        if not os.path.isfile(os.path.join(dest, ".complete")):
            shutil.rmtree(dest, ignore_errors=True)
            with tempfile.TemporaryDirectory() as tmp:
                # Any CPython's wheel has the same headers and libraries: ask for one every release has.
                cmd = [self.python, "-m", "pip", "download", "-q", "--disable-pip-version-check", "--no-deps"]
                cmd += ["--only-binary=:all:", "--python-version", "3.11", "-d", tmp]
                for tag in self.target.wheel_platforms:
                    cmd += ["--platform", tag]
                r = subprocess.run(cmd + [f"mitsuba=={version}", f"drjit=={drjit}"], stdout=sys.stderr)
                if r.returncode != 0:
                    raise BuildError(
                        f"could not download mitsuba=={version} and drjit=={drjit} for {self.target.name} "
                        "(their headers build its layer)"
                    )
                libcxx = set()
                for wheel in os.listdir(tmp):
                    with zipfile.ZipFile(os.path.join(tmp, wheel)) as z:
                        for name in z.namelist():
                            if self.wanted(name):
                                z.extract(name, dest)
                            elif self.zig and name.endswith((".dylib", ".so")):
                                libcxx |= libcxx_imports(z.read(name))
                if self.zig:
                    for d in ("mitsuba", "drjit"):
                        for f in os.listdir(os.path.join(dest, d)):
                            if f.endswith(".dylib"):
                                with open(os.path.join(dest, d, f), "rb") as fh:
                                    libcxx |= libcxx_imports(fh.read())
                    with open(os.path.join(dest, "libc++.imports"), "w") as f:
                        f.write("".join(name + "\n" for name in sorted(libcxx)))
            open(os.path.join(dest, ".complete"), "w").close()
        return Release(version, os.path.join(dest, "mitsuba"), os.path.join(dest, "drjit"), isa, "its wheel", dest)

    def releases(self):
        out = []
        for version, drjit, isa, installed in plan(self.target):
            if installed:
                _, _, mitsuba_dir, drjit_dir = installed
                if not os.path.isdir(os.path.join(mitsuba_dir, "include")):
                    raise BuildError(
                        f"the installed Mitsuba {version} ({mitsuba_dir}) has no include/ to build against"
                    )
                isa = detect_isa(self.target, mitsuba_dir)
                out.append(Release(version, mitsuba_dir, drjit_dir, isa, "installed", None))
            else:
                out.append(self.fetch(version, drjit, isa))
        return out

    # 3. The layers' objects.
    def defines(self, release):
        """The release's backends, as its headers need them declared (they change the layout of
        Mitsuba's classes): those of the variants its config.h lists, Embree (every wheel's CPU
        ray tracer) and autodiff."""
        config = open(os.path.join(release.mitsuba_dir, "include", "mitsuba", "core", "config.h")).read()
        variants = config.split("#define MI_VARIANTS", 1)[1].split("\n\n", 1)[0]
        backends = [b for b in ("LLVM", "CUDA", "METAL") if f'"{b.lower()}_' in variants]
        return [f"MI_ENABLE_{b}=1" for b in backends + ["EMBREE", "AUTODIFF"]] + ["NDEBUG"]

    def includes(self, release):
        nb = output([self.python, "-c", "import os, nanobind; print(os.path.dirname(nanobind.__file__))"]).strip()
        return [
            os.path.join(release.mitsuba_dir, "include"),
            os.path.join(release.drjit_dir, "include"),
            os.path.join(nb, "include"),
            os.path.join(nb, "ext", "robin_map", "include"),
            os.path.join(self.cargo_target, "cxxbridge"),
            os.path.join(self.cargo_target, "inc"),
        ]

    def flags(self, release):
        isa = self.target.isa_flags[release.isa]
        if self.target.os == "windows":
            return (
                ["/std:c++17", "/O2", "/EHsc", "/MD", "/bigobj", "/permissive-", "/Zc:__cplusplus", "/utf-8", *isa]
                + ["/DNOMINMAX", "/D_USE_MATH_DEFINES"]
                + ["/D" + d for d in self.defines(release)]
                + ["/I" + i for i in self.includes(release)]
            )
        # -O2: the layer is glue (the kernels are Rust's, optimised by cargo; the JIT variants
        # run it only while tracing). -O3 rendered no faster in scalar_rgb or llvm_ad_rgb
        # (bench_plugin, 3.9.1) and took 17 s per layer instead of 14.
        flags = ["-std=c++17", "-O2", "-fPIC", "-fvisibility=hidden", "-fno-strict-aliasing", *isa]
        if self.target.os == "macos":
            # As Mitsuba's own macOS libraries, which import no sized operator delete.
            flags.append("-fno-sized-deallocation")
        if self.target.os == "linux":
            # Releases built with the pre-C++11 string ABI (manylinux2014's toolchain) name no
            # std::__cxx11 symbol.
            library = os.path.join(release.mitsuba_dir, "libmitsuba.so")
            symbols = output([self.tool("nm"), "-D", "--defined-only", library])
            flags.append(f"-D_GLIBCXX_USE_CXX11_ABI={1 if '__cxx11' in symbols else 0}")
        return flags + ["-D" + d for d in self.defines(release)] + ["-I" + i for i in self.includes(release)]

    def object(self, release, src):
        return os.path.join(self.obj, release.version, src + (".obj" if self.target.os == "windows" else ".o"))

    def compile_layers(self, releases):
        jobs = []
        for release in releases:
            os.makedirs(os.path.join(self.obj, release.version), exist_ok=True)
            flags = self.flags(release)
            for src in ("plugin", "plugin_stub"):
                source, obj = os.path.join(ROOT, "cpp", src + ".cpp"), self.object(release, src)
                if self.target.os == "windows":
                    jobs.append([*self.cxx, *flags, "/c", source, "/Fo" + obj])
                else:
                    jobs.append([*self.cxx, *flags, "-c", source, "-o", obj])
        with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
            for r in pool.map(lambda cmd: subprocess.run(cmd, cwd=ROOT), jobs):
                if r.returncode != 0:
                    raise BuildError(f"compiling {' '.join(r.args[-3:])} failed")

    # 4. The kernels, once.
    def libcxx(self):
        """Zig's link against macOS's libc++ instead of Zig's own static libc++: a stub of the
        system library exporting what the Mach-O files of every release's wheels import from it
        (fetch() lists them; the wheels share one deployment target, so each is in macOS 11's
        libc++) and LIBCXX_ALSO."""
        if not self.zig:
            return []
        return ["-nostdlib++", os.path.join(self.obj, "libc++.tbd")]

    def write_libcxx_stub(self, releases):
        symbols = set(LIBCXX_ALSO)
        for release in releases:
            with open(os.path.join(release.root, "libc++.imports")) as f:
                symbols |= set(f.read().split())
        write_libcxx_stub(os.path.join(self.obj, "libc++.tbd"), sorted(symbols))

    def link_kernels(self, releases):
        lib = os.path.join(self.out, "lib")
        os.makedirs(lib, exist_ok=True)
        out = os.path.join(lib, self.target.library("matte_kernels"))
        if self.target.os == "windows":
            return  # linked into each layer (link.exe exports by .def only; no shared copy)
        if self.target.os == "macos":
            # The whole staticlib; a Mach-O image binds every import to the library it names
            # (two-level namespace), so its exports cannot meet another library's symbols.
            run(
                [*self.cxx, "-shared", "-o", out, "-Wl,-force_load," + self.staticlib()]
                + ["-Wl,-install_name,@rpath/" + os.path.basename(out), "-Wl,-dead_strip", "-Wl,-undefined,error"]
                + self.libcxx()
            )
            return
        nm = self.tool("nm")
        needed = set()
        for release in releases:
            for line in output([nm, "-u", "--format=posix", self.object(release, "plugin")]).splitlines():
                needed.add(line.split()[0])
        defined = set()
        for line in subprocess.run(
            [nm, "--defined-only", "--format=posix", self.staticlib()], capture_output=True, text=True
        ).stdout.splitlines():
            f = line.split()
            if len(f) >= 2 and f[1] in "TWVDRB":
                defined.add(f[0])
        exported = sorted(needed & defined)
        kernels_map = os.path.join(self.obj, "kernels.map")
        with open(kernels_map, "w") as f:
            f.write("{ global:\n" + "".join(s + ";\n" for s in exported) + "local: *; };\n")
        run(
            [*self.cxx, "-shared", "-o", out]
            + ["-Wl,--undefined=" + s for s in exported]
            + [self.staticlib(), "-Wl,--gc-sections", "-Wl,--version-script=" + kernels_map, "-s"]
            + ["-Wl,-soname," + os.path.basename(out), "-lpthread", "-ldl", "-lm"]
        )

    # 5. Each release's plugin folder.
    def link_layers(self, releases, types):
        for old in ("plugins", "releases"):  # plugins/: the single-release layout of earlier builds
            shutil.rmtree(os.path.join(self.out, old), ignore_errors=True)
        for release in releases:
            d = os.path.join(self.out, "releases", release.version, "plugins")
            os.makedirs(d)
            {"linux": self.link_elf, "macos": self.link_macho, "windows": self.link_pe}[self.target.os](
                release, d, types
            )

    def link_elf(self, release, d, types):
        cpp = os.path.join(ROOT, "cpp")
        layer = os.path.join(d, self.target.library("matte_bsdfs"))
        run(
            [*self.cxx, "-shared", "-o", layer, self.object(release, "plugin")]
            + ["-L" + os.path.join(self.out, "lib"), "-lmatte_kernels", "-Wl,-rpath,$ORIGIN/../../../lib"]
            + ["-Wl,--gc-sections", f"-Wl,--version-script={cpp}/exports.map", "-s"]
            + ["-L" + release.mitsuba_dir, "-L" + release.drjit_dir]
            + ["-l" + lib for lib in MITSUBA_LIBRARIES]
            + ["-Wl,-z,defs", "-lpthread", "-ldl", "-lm"]
        )
        for t in types:
            run(
                [*self.cxx, "-shared", "-o", os.path.join(d, t + ".so"), self.object(release, "plugin_stub")]
                + [f"-Wl,--version-script={cpp}/stub_exports.map", "-s", "-L" + d, "-lmatte_bsdfs"]
                + ["-Wl,-rpath,$ORIGIN", "-Wl,-z,defs"]
            )

    def link_macho(self, release, d, types):
        def exports(symbol):
            path = os.path.join(self.obj, symbol + ".exp")
            with open(path, "w") as f:
                f.write("_" + symbol + "\n")
            return "-Wl,-exported_symbols_list," + path

        common = ["-shared", "-Wl,-undefined,error", "-Wl,-dead_strip"] + self.libcxx()
        layer = os.path.join(d, self.target.library("matte_bsdfs"))
        # Mitsuba's and Dr.Jit's libraries are found where pip installs them beside matte_mitsuba
        # (site-packages/{mitsuba,drjit}); the process has loaded them already, by the same
        # install names (@rpath/libmitsuba.dylib, …).
        run(
            [*self.cxx, *common, "-o", layer, self.object(release, "plugin"), exports("matte_register")]
            + ["-Wl,-install_name,@rpath/" + os.path.basename(layer)]
            + ["-L" + os.path.join(self.out, "lib"), "-lmatte_kernels"]
            + ["-L" + release.mitsuba_dir, "-L" + release.drjit_dir]
            + ["-l" + lib for lib in MITSUBA_LIBRARIES]
            + ["-Wl,-rpath,@loader_path/" + p for p in ("../../../lib", "../../../../mitsuba", "../../../../drjit")]
        )
        for t in types:
            stub = os.path.join(d, t + self.target.plugin_suffix)
            run(
                [*self.cxx, *common, "-o", stub, self.object(release, "plugin_stub"), exports("init_plugin")]
                + ["-Wl,-install_name,@rpath/" + os.path.basename(stub)]
                + ["-L" + d, "-lmatte_bsdfs", "-Wl,-rpath,@loader_path"]
            )

    def link_pe(self, release, d, types):
        """MSVC: link.exe fails on an unresolved external by itself. Mitsuba's wheel has no
        import library for mitsuba.dll: one is made from the DLL's export table."""
        implib = os.path.join(self.obj, release.version, "mitsuba.lib")
        if not os.path.isfile(os.path.join(release.mitsuba_dir, "mitsuba.lib")):
            import lief

            names = [e.name for e in lief.parse(os.path.join(release.mitsuba_dir, "mitsuba.dll")).exported_functions]
            definition = implib[:-4] + ".def"
            with open(definition, "w") as f:
                f.write("LIBRARY mitsuba.dll\nEXPORTS\n" + "".join(f"    {n}\n" for n in names if n))
            run(["lib", "/nologo", "/machine:x64", "/def:" + definition, "/out:" + implib])
        else:
            implib = os.path.join(release.mitsuba_dir, "mitsuba.lib")
        libs = [implib] + [os.path.join(release.drjit_dir, lib + ".lib") for lib in MITSUBA_LIBRARIES[1:]]
        system = ["advapi32.lib", "bcrypt.lib", "kernel32.lib", "ntdll.lib", "userenv.lib", "ws2_32.lib"]
        layer = os.path.join(d, self.target.library("matte_bsdfs"))
        run(
            ["link", "/nologo", "/DLL", "/OPT:REF", "/OUT:" + layer, self.object(release, "plugin"), self.staticlib()]
            + libs
            + system
        )
        for t in types:
            run(
                ["link", "/nologo", "/DLL", "/OUT:" + os.path.join(d, t + ".dll"), self.object(release, "plugin_stub")]
                + [layer[:-4] + ".lib"]
            )

    # 6. The binary and _build.py.
    def finish(self, releases):
        bin_dir = os.path.join(self.out, "bin")
        os.makedirs(bin_dir, exist_ok=True)
        name = self.target.executable("matte")
        binary = os.path.join(bin_dir, name)
        shutil.copy2(os.path.join(self.rust_dir(), name), binary)
        if self.target.os == "linux":
            run([self.tool("strip"), binary])
        versions = ", ".join(f'"{r.version}"' for r in releases)
        with open(os.path.join(self.out, "_build.py"), "w") as f:
            f.write(
                '"""Generated by `cpp/build_plugin.py`; do not edit (rerun it)."""\n'
                f'PLATFORM = "{self.target.name}"\n'
                f"MITSUBA_RELEASES = ({versions},)\n"
                f'MODELS_JSON = r"""{self.host_matte("types", "--json").strip()}"""\n'
            )

    def build(self):
        self.build_rust()
        releases = self.releases()
        self.compile_layers(releases)
        if self.zig:
            self.write_libcxx_stub(releases)
        self.link_kernels(releases)
        types = self.host_matte("types").split()
        self.link_layers(releases, types)
        self.finish(releases)

        def kb(path):
            return os.path.getsize(path) // 1024 if os.path.isfile(path) else 0

        layer = self.target.library("matte_bsdfs")
        layers = "; ".join(
            f"{r.version} ({r.isa}, from {r.source}): {kb(os.path.join(self.out, 'releases', r.version, 'plugins', layer))} KB"
            for r in releases
        )
        kernels = self.target.library("matte_kernels")
        print(
            f"build_plugin: {self.target.name}: lib/{kernels} ({kb(os.path.join(self.out, 'lib', kernels))} KB) "
            f"and a layer per Mitsuba release ({layers}), plugins: {' '.join(types)}",
            file=sys.stderr,
        )


def libcxx_imports(data):
    """The symbols a Mach-O image (bytes) imports from libc++ or libc++abi: its undefined
    external symbols whose two-level library ordinal (n_desc >> 8) names one of them."""
    import lief

    lief.logging.disable()
    binary = lief.MachO.parse(list(data))
    if binary is None:
        return set()
    loads = {getattr(lief.MachO.LoadCommand.TYPE, t) for t in ("LOAD_DYLIB", "LOAD_WEAK_DYLIB", "REEXPORT_DYLIB")}
    out = set()
    for image in binary:
        libraries = [c.name for c in image.commands if c.command in loads]
        for s in image.symbols:
            if s.raw_type & 0x0E or not s.raw_type & 0x01:  # not N_UNDF | N_EXT
                continue
            ordinal = (s.description >> 8) & 0xFF
            if 1 <= ordinal <= len(libraries):
                if os.path.basename(libraries[ordinal - 1]).startswith(("libc++.", "libc++abi.")):
                    out.add(s.name)
    return out


def write_libcxx_stub(path, symbols):
    """A text-based stub (TAPI .tbd, which Zig's linker reads) of /usr/lib/libc++.1.dylib that
    exports `symbols`."""
    with open(path, "w") as f:
        f.write(
            "--- !tapi-tbd\ntbd-version: 4\ntargets: [ arm64-macos ]\n"
            "install-name: '/usr/lib/libc++.1.dylib'\ncurrent-version: 1200.3\n"
            "exports:\n  - targets: [ arm64-macos ]\n    symbols: [ "
            + ",\n               ".join(f"'{s}'" for s in symbols)
            + " ]\n...\n"
        )


def target_platform(name=None):
    """The platform to build for: `name`, else $MATTE_PLATFORM, else this machine's."""
    name = name or os.environ.get("MATTE_PLATFORM")
    if not name:
        return host_platform()
    if name not in PLATFORMS:
        raise BuildError(f"unknown platform {name!r} (MATTE_PLATFORM or --platform): one of {', '.join(PLATFORMS)}")
    return PLATFORMS[name]


def is_cross(target):
    return target.name != host_platform().name


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--platform", help="one of " + ", ".join(PLATFORMS) + " (default: this machine's)")
    parser.add_argument("--out", default=os.path.join(ROOT, "python", "matte_mitsuba"))
    args = parser.parse_args()
    try:
        Build(target_platform(args.platform), os.path.abspath(args.out)).build()
    except BuildError as e:
        sys.exit(f"build_plugin: {e}")


if __name__ == "__main__":
    main()
