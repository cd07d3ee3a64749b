#!/usr/bin/env bash
# Builds matte's Mitsuba plugin into python/matte_mitsuba/plugins/:
#   1. the Rust staticlib (the matte-plugin crate: kernels + cxx bridge glue) and the `matte` binary;
#   2. cpp/plugin.cpp against the Mitsuba/Dr.Jit headers of the Python that will load it
#      ($MATTE_PYTHON, default .venv/bin/python), with -march=x86-64-v3 to match the wheel's
#      Dr.Jit ABI;
#   3. libmatte_bsdfs.so (everything; exports only matte_register) and one small stub
#      <type>.so per plugin name (exports only init_plugin, forwards to the library);
#   4. matte_mitsuba/_build.py: the Mitsuba version the plugin was compiled against.
# Called by setup.py (the wheel) and, through it, by `make plugin`.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

PYTHON=${MATTE_PYTHON:-.venv/bin/python}
# Where the wheels are (an isolated build puts them in an overlay, not in site-packages).
where() { "$PYTHON" -c "import os, $1; print(os.path.dirname($1.__file__))"; }
MI=$(where mitsuba)
DR=$(where drjit)
NB=$(where nanobind)
MITSUBA_VERSION=$("$PYTHON" -c 'import mitsuba; print(mitsuba.__version__)')
PKG=python/matte_mitsuba
OUT=$PKG/plugins
OBJ=target/plugin
mkdir -p "$OUT" "$OBJ"

# libmatte_plugin.a and the cxx headers (the matte-plugin crate: matte-brdf beneath it, nothing
# else of matte), and the matte binary (the matte crate, for the type list below).
cargo build --release --quiet -p matte-plugin -p matte
# The generated bridge header includes "matte/cpp/arena.h" (build.rs sets the prefix `matte`).
mkdir -p target/inc && ln -sfn "$PWD" target/inc/matte

CXXFLAGS=(-std=c++17 -O3 -fPIC -fvisibility=hidden -fno-strict-aliasing -march=x86-64-v3
          -DMI_ENABLE_LLVM=1 -DMI_ENABLE_CUDA=1 -DMI_ENABLE_EMBREE=1 -DMI_ENABLE_AUTODIFF=1 -DNDEBUG
          -I"$MI/include" -I"$DR/include" -I"$NB/include"
          -I"$NB/ext/robin_map/include" -Itarget/cxxbridge -Itarget/inc)
MILIBS=(-L"$MI" -L"$DR" -lmitsuba -ldrjit-core -ldrjit-extra -lnanothread -lpthread -ldl -lm)
g++ "${CXXFLAGS[@]}" -c cpp/plugin.cpp -o "$OBJ/plugin.o"
g++ "${CXXFLAGS[@]}" -c cpp/plugin_stub.cpp -o "$OBJ/plugin_stub.o"
g++ -shared -o "$OUT/libmatte_bsdfs.so" "$OBJ/plugin.o" target/release/libmatte_plugin.a \
    -Wl,--gc-sections -Wl,--version-script=cpp/exports.map -s "${MILIBS[@]}"
rm -f "$OUT/matte_bsdfs.so"   # the single-library layout of earlier builds
# One stub per registered type (`matte types`: the models and tabulated_brdf).
for t in $(./target/release/matte types); do
    rm -f "$OUT/$t.so"
    g++ -shared -o "$OUT/$t.so" "$OBJ/plugin_stub.o" -Wl,--version-script=cpp/stub_exports.map -s \
        -L"$OUT" -lmatte_bsdfs -Wl,-rpath,'$ORIGIN'
done
# The Mitsuba version and the model registry (`matte types --json`) for matte_mitsuba.MODELS.
printf '"""Written by cpp/build_plugin.sh."""\nMITSUBA_VERSION = "%s"\nMODELS_JSON = r"""%s"""\n' \
    "$MITSUBA_VERSION" "$(./target/release/matte types --json)" > "$PKG/_build.py"
echo "build_plugin: $OUT/libmatte_bsdfs.so ($(du -k "$OUT/libmatte_bsdfs.so" | cut -f1) KB) for Mitsuba $MITSUBA_VERSION, plugins: $(./target/release/matte types | tr '\n' ' ')"
