#!/usr/bin/env python3
"""Builds matte's Mitsuba plugin for one platform, for every Mitsuba release of
cpp/mitsuba_releases.txt published there (and the installed one, when the table lacks it):

 1. once: the Rust staticlib (the matte-plugin crate: kernels + cxx bridge glue) and the `matte`
    binary, for the platform's Rust target;
 2. per release: its headers and libraries (mitsuba/include, libmitsuba.so, drjit/include and
    Dr.Jit's libraries), taken from that release's mitsuba and drjit wheels for the platform,
    downloaded from the package index by pip and cached in $MATTE_MITSUBA_CACHE (default
    ~/.cache/matte-mitsuba), or from the installed Mitsuba for a release the table lacks;
 3. per release: cpp/plugin.cpp compiled against them with that release's instruction set and
    C++ string ABI (the release's C++ layer), in parallel;
 4. once: lib/libmatte_kernels.so, the Rust kernels with exactly the bridge symbols the layers
    call (the union of their undefined symbols), so the kernels ship once;
 5. per release: releases/<release>/plugins/libmatte_bsdfs.so (the layer, linked against the
    kernels and the release's libmitsuba.so with undefined symbols an error; exports only
    matte_register) and one small stub <type>.so per plugin name (exports only init_plugin,
    forwards to the layer);
 6. bin/matte (stripped) and _build.py: the platform, the releases built and the model registry.

    python3 cpp/build_plugin.py [--platform linux-x86_64|linux-aarch64] [--out DIR]

The platform defaults to this machine's; another one is cross-built (linux-aarch64 on x86-64:
Debian's g++-aarch64-linux-gnu and Rust's aarch64-unknown-linux-gnu target). DIR defaults to
python/matte_mitsuba. MATTE_MITSUBA_RELEASES="3.9.1 3.8.0" builds a subset of the table (a
development shortcut; a wheel for users holds every release). The installed Mitsuba is the one
of $MATTE_MITSUBA_PYTHON, else of the Python running this script (outside pip's build
isolation); a release of it that the table lacks gets a layer from its own headers. setup.py
calls this for the wheel, and `make plugin`/`make dist` through it.
"""

import argparse
import concurrent.futures
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
    machine: str  # platform.machine() where it runs natively
    rust_target: str
    tool_prefix: str  # of the cross toolchain (g++, nm, strip), used when cross-building
    cross_packages: str  # the Debian packages that provide that toolchain
    wheel_platforms: tuple  # pip --platform tags that find Mitsuba's wheels
    wheel_tag: str  # the tag of matte's own (unrepaired) wheel
    # Compiler flags per instruction set of the table's column.
    isa_flags: dict


PLATFORMS = {
    p.name: p
    for p in (
        Platform(
            "linux-x86_64",
            "x86_64",
            "x86_64-unknown-linux-gnu",
            "x86_64-linux-gnu-",
            "g++-x86-64-linux-gnu",
            ("manylinux_2_28_x86_64", "manylinux_2_17_x86_64", "manylinux2014_x86_64"),
            "linux_x86_64",
            {"avx": ["-mavx"], "x86-64-v3": ["-march=x86-64-v3"]},
        ),
        Platform(
            "linux-aarch64",
            "aarch64",
            "aarch64-unknown-linux-gnu",
            "aarch64-linux-gnu-",
            "g++-aarch64-linux-gnu",
            ("manylinux_2_28_aarch64", "manylinux_2_17_aarch64", "manylinux2014_aarch64"),
            "linux_aarch64",
            {"armv8-a": ["-march=armv8-a"]},
        ),
    )
}
# The libraries each layer links against, from the mitsuba and drjit wheels (not shipped).
MITSUBA_LIBRARIES = ["mitsuba", "drjit-core", "drjit-extra", "nanothread"]


class BuildError(Exception):
    pass


def host_platform():
    machine = platform.machine()
    for p in PLATFORMS.values():
        if p.machine == machine and sys.platform.startswith("linux"):
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
    """The instruction set an installed Mitsuba was compiled for, read from its library: on
    x86-64, x86-64-v3 when it holds FMA instructions, else avx."""
    if target.name == "linux-aarch64":
        return "armv8-a"
    lib = os.path.join(mitsuba_dir, "libmitsuba.so")
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
    mitsuba_dir: str  # holds include/ and libmitsuba.so
    drjit_dir: str  # holds include/ and Dr.Jit's libraries
    isa: str
    source: str  # where its headers came from, for the summary


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
        self.cxx = self.tool("g++")

    def tool(self, name):
        """The toolchain's `name` for the target: the cross one when cross-building."""
        if not self.cross:
            return name
        path = shutil.which(self.target.tool_prefix + name)
        if not path:
            raise BuildError(
                f"cross-building for {self.target.name} needs {self.target.tool_prefix}{name} "
                f"(Debian: apt-get install {self.target.cross_packages})"
            )
        return path

    # 1. Rust.
    def rust_dir(self):
        """Where cargo puts the target's release artifacts."""
        if self.cross:
            return os.path.join(self.cargo_target, self.target.rust_target, "release")
        return os.path.join(self.cargo_target, "release")

    def build_rust(self):
        cmd = ["cargo", "build", "--release", "--quiet", "-p", "matte-plugin", "-p", "matte"]
        if self.cross:
            installed = output(["rustup", "target", "list", "--installed"]) if shutil.which("rustup") else ""
            if self.target.rust_target not in installed.split():
                raise BuildError(
                    f"cross-building for {self.target.name} needs Rust's {self.target.rust_target} target "
                    f"(rustup target add {self.target.rust_target})"
                )
            cmd += ["--target", self.target.rust_target]
            # The cxx bridge's C++ (cc) for the target, with the target's compiler.
            triple = self.target.rust_target.replace("-", "_")
            os.environ.setdefault("CXX_" + triple, self.cxx)
            os.environ.setdefault("CC_" + triple, self.tool("gcc"))
            os.environ.setdefault("AR_" + triple, self.tool("ar"))
        run(cmd, cwd=ROOT)
        if self.cross:
            # The type list and the registry come from a matte that runs here: the native build's
            # (the same packages, so the same features: nothing to build after a native build).
            run(cmd[: cmd.index("--target")], cwd=ROOT)
        # The generated bridge header includes "matte/cpp/arena.h" (build.rs sets the prefix `matte`).
        inc = os.path.join(self.cargo_target, "inc")
        os.makedirs(inc, exist_ok=True)
        link = os.path.join(inc, "matte")
        if os.path.realpath(link) != ROOT:
            if os.path.lexists(link):
                os.remove(link)
            os.symlink(ROOT, link)

    def host_matte(self, *args):
        return output([os.path.join(self.cargo_target, "release", "matte"), *args])

    # 2. Headers and libraries.
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
                for wheel in os.listdir(tmp):
                    package = wheel.split("-")[0]
                    with zipfile.ZipFile(os.path.join(tmp, wheel)) as z:
                        for name in z.namelist():
                            base = os.path.basename(name)
                            if name.startswith(package + "/include/") or (
                                name.count("/") == 1 and base.startswith("lib") and ".so" in base
                            ):
                                z.extract(name, dest)
            open(os.path.join(dest, ".complete"), "w").close()
        return Release(version, os.path.join(dest, "mitsuba"), os.path.join(dest, "drjit"), isa, "its wheel")

    def releases(self):
        out = []
        for version, drjit, isa, installed in plan(self.target):
            if installed:
                _, _, mitsuba_dir, drjit_dir = installed
                if not os.path.isdir(os.path.join(mitsuba_dir, "include")):
                    raise BuildError(
                        f"the installed Mitsuba {version} ({mitsuba_dir}) has no include/ to build against"
                    )
                out.append(Release(version, mitsuba_dir, drjit_dir, detect_isa(self.target, mitsuba_dir), "installed"))
            else:
                out.append(self.fetch(version, drjit, isa))
        return out

    # 3. The layers' objects.
    def flags(self, release):
        nb = output([self.python, "-c", "import os, nanobind; print(os.path.dirname(nanobind.__file__))"]).strip()
        # Releases built with the pre-C++11 string ABI (manylinux2014's toolchain) name no
        # std::__cxx11 symbol.
        symbols = output([self.tool("nm"), "-D", "--defined-only", os.path.join(release.mitsuba_dir, "libmitsuba.so")])
        abi = 1 if "__cxx11" in symbols else 0
        return [
            "-std=c++17",
            "-O3",
            "-fPIC",
            "-fvisibility=hidden",
            "-fno-strict-aliasing",
            *self.target.isa_flags[release.isa],
            f"-D_GLIBCXX_USE_CXX11_ABI={abi}",
            "-DMI_ENABLE_LLVM=1",
            "-DMI_ENABLE_CUDA=1",
            "-DMI_ENABLE_EMBREE=1",
            "-DMI_ENABLE_AUTODIFF=1",
            "-DNDEBUG",
            "-I" + os.path.join(release.mitsuba_dir, "include"),
            "-I" + os.path.join(release.drjit_dir, "include"),
            "-I" + os.path.join(nb, "include"),
            "-I" + os.path.join(nb, "ext", "robin_map", "include"),
            "-I" + os.path.join(self.cargo_target, "cxxbridge"),
            "-I" + os.path.join(self.cargo_target, "inc"),
        ]

    def compile_layers(self, releases):
        jobs = []
        for release in releases:
            d = os.path.join(self.obj, release.version)
            os.makedirs(d, exist_ok=True)
            flags = self.flags(release)
            for src in ("plugin", "plugin_stub"):
                jobs.append([self.cxx, *flags, "-c", os.path.join(ROOT, "cpp", src + ".cpp"), "-o", f"{d}/{src}.o"])
        with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
            for r in pool.map(lambda cmd: subprocess.run(cmd, cwd=ROOT), jobs):
                if r.returncode != 0:
                    raise BuildError(f"compiling {' '.join(r.args[-3:])} failed")

    # 4. The kernels, once.
    def link_kernels(self, releases):
        nm = self.tool("nm")
        staticlib = os.path.join(self.rust_dir(), "libmatte_plugin.a")
        needed = set()
        for release in releases:
            for line in output([nm, "-u", "--format=posix", f"{self.obj}/{release.version}/plugin.o"]).splitlines():
                needed.add(line.split()[0])
        defined = set()
        for line in subprocess.run(
            [nm, "--defined-only", "--format=posix", staticlib], capture_output=True, text=True
        ).stdout.splitlines():
            f = line.split()
            if len(f) >= 2 and f[1] in "TWVDRB":
                defined.add(f[0])
        exported = sorted(needed & defined)
        kernels_map = os.path.join(self.obj, "kernels.map")
        with open(kernels_map, "w") as f:
            f.write("{ global:\n" + "".join(s + ";\n" for s in exported) + "local: *; };\n")
        lib = os.path.join(self.out, "lib")
        os.makedirs(lib, exist_ok=True)
        run(
            [self.cxx, "-shared", "-o", os.path.join(lib, "libmatte_kernels.so")]
            + ["-Wl,--undefined=" + s for s in exported]
            + [staticlib, "-Wl,--gc-sections", "-Wl,--version-script=" + kernels_map, "-s"]
            + ["-Wl,-soname,libmatte_kernels.so", "-lpthread", "-ldl", "-lm"]
        )

    # 5. Each release's plugin folder.
    def link_layers(self, releases, types):
        for old in ("plugins", "releases"):  # plugins/: the single-release layout of earlier builds
            shutil.rmtree(os.path.join(self.out, old), ignore_errors=True)
        cpp = os.path.join(ROOT, "cpp")
        for release in releases:
            d = os.path.join(self.out, "releases", release.version, "plugins")
            os.makedirs(d)
            o = os.path.join(self.obj, release.version)
            run(
                [self.cxx, "-shared", "-o", f"{d}/libmatte_bsdfs.so", f"{o}/plugin.o"]
                + ["-L" + os.path.join(self.out, "lib"), "-lmatte_kernels", "-Wl,-rpath,$ORIGIN/../../../lib"]
                + ["-Wl,--gc-sections", f"-Wl,--version-script={cpp}/exports.map", "-s"]
                + ["-L" + release.mitsuba_dir, "-L" + release.drjit_dir]
                + ["-l" + lib for lib in MITSUBA_LIBRARIES]
                + ["-Wl,-z,defs", "-lpthread", "-ldl", "-lm"]
            )
            for t in types:
                run(
                    [self.cxx, "-shared", "-o", f"{d}/{t}.so", f"{o}/plugin_stub.o"]
                    + [f"-Wl,--version-script={cpp}/stub_exports.map", "-s", "-L" + d, "-lmatte_bsdfs"]
                    + ["-Wl,-rpath,$ORIGIN"]
                )

    # 6. The binary and _build.py.
    def finish(self, releases):
        bin_dir = os.path.join(self.out, "bin")
        os.makedirs(bin_dir, exist_ok=True)
        binary = os.path.join(bin_dir, "matte")
        shutil.copy2(os.path.join(self.rust_dir(), "matte"), binary)
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
        self.link_kernels(releases)
        types = self.host_matte("types").split()
        self.link_layers(releases, types)
        self.finish(releases)

        def kb(path):
            return os.path.getsize(path) // 1024

        layers = "; ".join(
            f"{r.version} ({r.isa}, from {r.source}): "
            f"{kb(os.path.join(self.out, 'releases', r.version, 'plugins', 'libmatte_bsdfs.so'))} KB"
            for r in releases
        )
        print(
            f"build_plugin: {self.target.name}: lib/libmatte_kernels.so "
            f"({kb(os.path.join(self.out, 'lib', 'libmatte_kernels.so'))} KB) and a layer per Mitsuba release "
            f"({layers}), plugins: {' '.join(types)}",
            file=sys.stderr,
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
