#!/usr/bin/env bash
# Builds matte's Mitsuba plugin (recipe: shared/docs/mitsuba-plugin.md):
#   1. the Rust staticlib (kernels + cxx bridge glue) and the `matte` binary;
#   2. cpp/plugin.cpp against the pinned wheels' headers (.venv, set up by
#      validation/setup_venv.sh), with -march=x86-64-v3 to match the wheel's Dr.Jit ABI;
#   3. one shared library exporting only init_plugin, and <type>.so links to it for every
#      plugin name, in validation/matte_mitsuba/plugins/.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

SP=$(.venv/bin/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
OUT=validation/matte_mitsuba/plugins
OBJ=target/plugin
mkdir -p "$OUT" "$OBJ"

cargo build --release --quiet   # libmatte.a, the cxx headers, and the matte binary
# The generated bridge header includes "matte/cpp/arena.h" (crate-relative).
mkdir -p target/inc && ln -sfn "$PWD" target/inc/matte

CXXFLAGS=(-std=c++17 -O3 -fPIC -fvisibility=hidden -fno-strict-aliasing -march=x86-64-v3
          -DMI_ENABLE_LLVM=1 -DMI_ENABLE_CUDA=1 -DMI_ENABLE_EMBREE=1 -DMI_ENABLE_AUTODIFF=1 -DNDEBUG
          -I"$SP/mitsuba/include" -I"$SP/drjit/include" -I"$SP/nanobind/include"
          -I"$SP/nanobind/ext/robin_map/include" -Itarget/cxxbridge -Itarget/inc)
g++ "${CXXFLAGS[@]}" -c cpp/plugin.cpp -o "$OBJ/plugin.o"
g++ -shared -o "$OUT/matte_bsdfs.so" "$OBJ/plugin.o" target/release/libmatte.a \
    -Wl,--gc-sections -Wl,--version-script=cpp/exports.map -s \
    -L"$SP/mitsuba" -L"$SP/drjit" -lmitsuba -ldrjit-core -ldrjit-extra -lnanothread -lpthread -ldl -lm
for t in lambert oren_nayar eon wolff ginneken roughdiffuse; do
    ln -sf matte_bsdfs.so "$OUT/$t.so"
done
echo "build_plugin: $OUT/matte_bsdfs.so ($(du -k "$OUT/matte_bsdfs.so" | cut -f1) KB), exports: $(nm -D --defined-only "$OUT/matte_bsdfs.so" | awk '{print $3}' | tr '\n' ' ')"
