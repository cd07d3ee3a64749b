"""The macOS arm64 wheel (`make dist`: cross-built with Zig, cpp/build_plugin.py). It cannot run
here; what can be checked is checked, on the wheel's own files, with lief reading Mach-O:

* the tag, the metadata and a layout that is the Linux wheel's with macOS's suffixes;
* every binary is arm64 for macOS 11.0 (the deployment target of Mitsuba's macOS wheels) and
  code-signed (arm64 macOS runs no unsigned code);
* install names are @rpath/<file>, rpaths are relative to the loading file and lead to the
  package's own folders, and each file loads only macOS's libSystem and libc++, Mitsuba's and
  Dr.Jit's libraries and matte's own;
* every symbol a layer imports is exported by the library its two-level ordinal names: the
  release's libmitsuba/libdrjit-* of its macOS wheel (read from those files), matte's kernels,
  or the system's (libSystem's stub in Zig; libc++'s as the build's stub lists it);
* the link check itself: a layer relinked without one of the symbols it imports fails, naming
  it, and relinked with everything succeeds.
"""

import glob
import os
import re
import sys
import zipfile

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "cpp"))
import build_plugin  # noqa: E402

lief = pytest.importorskip("lief")
lief.logging.disable()

TARGET = build_plugin.PLATFORMS["macos-arm64"]
SYSTEM = {"/usr/lib/libSystem.B.dylib", "/usr/lib/libc++.1.dylib"}
MITSUBA = {"@rpath/" + TARGET.library(n) for n in build_plugin.MITSUBA_LIBRARIES}
OWN = {"@rpath/libmatte_kernels.dylib", "@rpath/libmatte_bsdfs.dylib"}
LOADS = {getattr(lief.MachO.LoadCommand.TYPE, t) for t in ("LOAD_DYLIB", "LOAD_WEAK_DYLIB", "REEXPORT_DYLIB")}


def wheel(pattern):
    found = glob.glob(os.path.join(REPO, "dist", pattern))
    assert len(found) == 1, f"make dist makes one {pattern}: {found}"
    return found[0]


@pytest.fixture(scope="module")
def macos_wheel():
    path = wheel("matte_mitsuba-*-py3-none-macosx_11_0_arm64.whl")
    with zipfile.ZipFile(path) as z:
        return path, {n: z.read(n) for n in z.namelist()}


def macho(data):
    binary = lief.MachO.parse(list(data))
    assert binary is not None and binary.size == 1, "one arm64 image, not a fat file"
    return binary.at(0)


def releases():
    return [row[0] for row in build_plugin.read_table() if row[2]["macos-arm64"]]


def imports(image):
    """{library: {symbol}} by two-level ordinal."""
    libraries = [c.name for c in image.commands if c.command in LOADS]
    out = {}
    for s in image.symbols:
        if s.raw_type & 0x0E or not s.raw_type & 0x01:  # undefined external symbols only
            continue
        ordinal = (s.description >> 8) & 0xFF
        assert 1 <= ordinal <= len(libraries), f"{s.name}: ordinal {ordinal} (flat or dynamic lookup)"
        out.setdefault(libraries[ordinal - 1], set()).add(s.name)
    return out


def exports(image):
    return {s.name for s in image.exported_symbols}


def test_the_wheel_is_tagged_and_laid_out_as_the_linux_one(macos_wheel):
    path, files = macos_wheel
    assert os.path.basename(path).endswith("-py3-none-macosx_11_0_arm64.whl")
    meta = next(v for n, v in files.items() if n.endswith(".dist-info/WHEEL")).decode()
    assert "Root-Is-Purelib: false" in meta and "Tag: py3-none-macosx_11_0_arm64" in meta, meta
    requires = next(v for n, v in files.items() if n.endswith(".dist-info/METADATA")).decode()
    published = releases()
    assert f"Requires-Dist: mitsuba<={published[-1]},>={published[0]}" in requires, requires
    with zipfile.ZipFile(wheel("matte_mitsuba-*-py3-none-linux_x86_64.whl")) as z:  # as built, before repair
        linux = {n for n in z.namelist() if ".dist-info/" not in n and not n.endswith("/")}
    mac = {n for n in files if ".dist-info/" not in n}
    assert {re.sub(r"\.dylib$", ".so", n) for n in mac} == linux, sorted(
        {re.sub(r"\.dylib$", ".so", n) for n in mac} ^ linux
    )[:10]
    build = files["matte_mitsuba/_build.py"].decode()
    assert 'PLATFORM = "macos-arm64"' in build, build[:200]
    # Zig's c++, asked for --version by build.rs's cc, writes an empty a.o where it runs.
    assert not os.path.exists(os.path.join(REPO, "a.o")), "the macOS build left a.o in the checkout"


def test_every_binary_is_arm64_macos_11_signed_with_relative_names(macos_wheel):
    _, files = macos_wheel
    binaries = {n: d for n, d in files.items() if d[:4] == b"\xcf\xfa\xed\xfe"}
    published = releases()
    assert len(binaries) == 2 + len(published) * (1 + len(build_plugin_types(files))), sorted(binaries)
    for name, data in binaries.items():
        image = macho(data)
        assert image.header.cpu_type == lief.MachO.Header.CPU_TYPE.ARM64, name
        assert list(image.build_version.minos) == [11, 0, 0], (name, image.build_version.minos)
        assert image.has_code_signature, name
        loads = {c.name for c in image.commands if c.command in LOADS}
        if name.endswith("/bin/matte"):
            assert all(n.startswith("/usr/lib/") for n in loads), loads
            continue
        ids = [c.name for c in image.commands if c.command == lief.MachO.LoadCommand.TYPE.ID_DYLIB]
        assert ids == ["@rpath/" + os.path.basename(name)], (name, ids)
        assert loads <= SYSTEM | MITSUBA | OWN, (name, loads - SYSTEM - MITSUBA - OWN)
        for rpath in (r.path for r in image.rpaths):
            assert rpath.startswith("@loader_path"), (name, rpath)
            target = os.path.normpath(os.path.join(os.path.dirname(name), rpath.replace("@loader_path", ".")))
            # Into the package, or to the mitsuba and drjit packages installed beside it.
            assert any(n.startswith(target + "/") for n in files) or os.path.basename(target) in ("mitsuba", "drjit"), (
                name,
                rpath,
            )
        exported = {s for s in exports(image) if not s.startswith(("__mh_", "___dso"))}
        if os.path.basename(name) == "libmatte_bsdfs.dylib":
            assert exported == {"_matte_register"}, exported
        elif "/plugins/" in name:
            assert exported == {"_init_plugin"}, (name, exported)


def build_plugin_types(files):
    return sorted(
        os.path.basename(n)[: -len(".dylib")]
        for n in files
        if f"/releases/{releases()[-1]}/plugins/" in n and not n.endswith("libmatte_bsdfs.dylib")
    )


def cached_release(version):
    """The release's macOS wheel's libraries, as the build downloaded them."""
    build = build_plugin.Build(TARGET, os.path.join(REPO, "target", "test-macos"))
    row = next(r for r in build_plugin.read_table() if r[0] == version)
    return build, build.fetch(version, row[1], "arm64")


@pytest.mark.parametrize("version", releases())
def test_every_import_of_a_layer_is_exported_where_it_is_bound(macos_wheel, version):
    _, files = macos_wheel
    _, release = cached_release(version)
    layer = macho(files[f"matte_mitsuba/releases/{version}/plugins/libmatte_bsdfs.dylib"])
    kernels = exports(macho(files["matte_mitsuba/lib/libmatte_kernels.dylib"]))
    provided = {"@rpath/libmatte_kernels.dylib": kernels}
    for lib in build_plugin.MITSUBA_LIBRARIES:
        folder = release.mitsuba_dir if lib == "mitsuba" else release.drjit_dir
        with open(os.path.join(folder, TARGET.library(lib)), "rb") as f:
            provided["@rpath/" + TARGET.library(lib)] = exports(macho(f.read()))
    with open(os.path.join(REPO, "target", "plugin", "macos-arm64", "libc++.tbd")) as f:
        provided["/usr/lib/libc++.1.dylib"] = set(re.findall(r"'([^']+)'", f.read()))
    zig = os.path.dirname(__import__("ziglang").__file__)
    with open(os.path.join(zig, "lib", "libc", "darwin", "libSystem.tbd")) as f:
        provided["/usr/lib/libSystem.B.dylib"] = set(re.findall(r"[\w$.]+", f.read()))
    found = imports(layer)
    assert found.keys() <= provided.keys(), found.keys() - provided.keys()
    assert "@rpath/libmitsuba.dylib" in found and "@rpath/libmatte_kernels.dylib" in found, found.keys()
    for library, symbols in found.items():
        assert symbols <= provided[library], (library, sorted(symbols - provided[library])[:5])


@pytest.mark.parametrize("drop", ["a libc++ symbol", "libmitsuba"])
def test_the_link_fails_when_a_symbol_is_missing(macos_wheel, tmp_path, capfd, drop, monkeypatch):
    _, files = macos_wheel
    version = releases()[-1]
    build, release = cached_release(version)
    build.out = str(tmp_path)
    os.makedirs(tmp_path / "lib")
    (tmp_path / "lib" / "libmatte_kernels.dylib").write_bytes(files["matte_mitsuba/lib/libmatte_kernels.dylib"])
    stub = os.path.join(REPO, "target", "plugin", "macos-arm64", "libc++.tbd")
    symbols = re.findall(r"'([^']+)'", open(stub).read())
    layer = macho(files[f"matte_mitsuba/releases/{version}/plugins/libmatte_bsdfs.dylib"])
    victim = sorted(imports(layer)["/usr/lib/libc++.1.dylib"])[0]

    def link(symbols):
        build_plugin.write_libcxx_stub(str(tmp_path / "libc++.tbd"), symbols)
        build.libcxx = lambda: ["-nostdlib++", str(tmp_path / "libc++.tbd")]
        d = tmp_path / "plugins"
        d.mkdir(exist_ok=True)
        build.link_macho(release, str(d), ["lambert"])

    link(symbols)  # everything there: it links
    capfd.readouterr()
    if drop == "libmitsuba":
        monkeypatch.setattr(build_plugin, "MITSUBA_LIBRARIES", build_plugin.MITSUBA_LIBRARIES[1:])
        missing = "__ZN7mitsuba"
    else:
        symbols = [s for s in symbols if s != victim]
        missing = victim
    with pytest.raises(build_plugin.BuildError):
        link(symbols)
    err = capfd.readouterr().err
    assert f"undefined symbol: {missing}" in err, err[-2000:]
