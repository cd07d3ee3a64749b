#!/usr/bin/env bash
# Builds matte's Mitsuba plugin into python/matte_mitsuba/, for every Mitsuba release of
# cpp/mitsuba_releases.txt:
#   1. once: the Rust staticlib (the matte-plugin crate: kernels + cxx bridge glue) and the
#      `matte` binary;
#   2. per release: its headers and libraries (mitsuba/include, libmitsuba.so, drjit/include and
#      Dr.Jit's libraries), taken from that release's mitsuba and drjit wheels, downloaded from the
#      package index by pip and cached in $MATTE_MITSUBA_CACHE (default ~/.cache/matte-mitsuba);
#   3. per release: cpp/plugin.cpp compiled against them with that release's instruction set and
#      C++ string ABI (the release's C++ layer), in parallel;
#   4. once: lib/libmatte_kernels.so, the Rust kernels with exactly the bridge symbols the layers
#      call (the union of their undefined symbols), so the kernels ship once;
#   5. per release: releases/<release>/plugins/libmatte_bsdfs.so (the layer, linked against the
#      kernels and the release's libmitsuba.so; exports only matte_register) and one small stub
#      <type>.so per plugin name (exports only init_plugin, forwards to the layer);
#   6. matte_mitsuba/_build.py: the releases built and the model registry.
# MATTE_MITSUBA_RELEASES="3.9.1 3.8.0" builds a subset (a development shortcut; a wheel for users
# holds every release). Called by setup.py (the wheel) and, through it, by `make plugin`.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

PYTHON=${MATTE_PYTHON:-.venv/bin/python}
CACHE=${MATTE_MITSUBA_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/matte-mitsuba}
PKG=python/matte_mitsuba
OBJ=target/plugin
mkdir -p "$OBJ" "$CACHE"

# The releases to build: the table's, or the subset asked for (each must be in the table).
mapfile -t TABLE < <(grep -v '^#' cpp/mitsuba_releases.txt | grep .)
RELEASES=()
for line in "${TABLE[@]}"; do
    read -r release _ <<<"$line"
    if [ -z "${MATTE_MITSUBA_RELEASES:-}" ] || [[ " ${MATTE_MITSUBA_RELEASES//,/ } " == *" $release "* ]]; then
        RELEASES+=("$release")
    fi
done
[ ${#RELEASES[@]} -gt 0 ] || { echo "build_plugin: MATTE_MITSUBA_RELEASES='$MATTE_MITSUBA_RELEASES' names none of cpp/mitsuba_releases.txt" >&2; exit 1; }
column() { grep -v '^#' cpp/mitsuba_releases.txt | awk -v r="$1" -v c="$2" '$1 == r {print $c}'; }

# nanobind's intrusive reference counting (mitsuba/core/object.h includes it): header-only, the
# same in every release.
NB=$("$PYTHON" -c 'import os, nanobind; print(os.path.dirname(nanobind.__file__))')

# 2. The release's headers and libraries, fetched once into the cache.
fetch() {
    local release=$1 drjit dest tmp
    drjit=$(column "$release" 2)
    dest=$CACHE/$release
    [ -f "$dest/.complete" ] && return
    rm -rf "$dest"
    tmp=$(mktemp -d)
    # Any CPython's wheel has the same headers and libraries: ask for one every release has.
    "$PYTHON" -m pip download -q --disable-pip-version-check --no-deps --only-binary=:all: \
        --python-version 3.11 --platform manylinux_2_28_x86_64 --platform manylinux_2_17_x86_64 \
        --platform manylinux2014_x86_64 -d "$tmp" "mitsuba==$release" "drjit==$drjit" >&2 ||
        { echo "build_plugin: could not download mitsuba==$release and drjit==$drjit (their headers build its layer)" >&2; exit 1; }
    mkdir -p "$dest"
    (cd "$dest" && unzip -q "$tmp"/mitsuba-*.whl 'mitsuba/include/*' mitsuba/libmitsuba.so &&
        unzip -q "$tmp"/drjit-*.whl 'drjit/include/*' 'drjit/lib*.so')
    rm -rf "$tmp"
    touch "$dest/.complete"
}

# 1. The Rust side: libmatte_plugin.a and the cxx headers (the matte-plugin crate: matte-brdf
# beneath it, nothing else of matte), and the matte binary (the matte crate, for the type list).
cargo build --release --quiet -p matte-plugin -p matte
# The generated bridge header includes "matte/cpp/arena.h" (build.rs sets the prefix `matte`).
mkdir -p target/inc && ln -sfn "$PWD" target/inc/matte
for release in "${RELEASES[@]}"; do fetch "$release"; done

# 3. One layer object per release, compiled in parallel.
flags() {
    local release=$1 dir=$CACHE/$1 isa abi=1
    case $(column "$release" 3) in
        avx) isa=-mavx ;;
        x86-64-v3) isa=-march=x86-64-v3 ;;
        *) echo "build_plugin: unknown instruction set for $release in cpp/mitsuba_releases.txt" >&2; exit 1 ;;
    esac
    # Releases built with the pre-C++11 string ABI (manylinux2014's toolchain) name no
    # std::__cxx11 symbol.
    [ "$(nm -D --defined-only "$dir/mitsuba/libmitsuba.so" | grep -c __cxx11)" -gt 0 ] || abi=0
    echo -std=c++17 -O3 -fPIC -fvisibility=hidden -fno-strict-aliasing "$isa" -D_GLIBCXX_USE_CXX11_ABI=$abi \
        -DMI_ENABLE_LLVM=1 -DMI_ENABLE_CUDA=1 -DMI_ENABLE_EMBREE=1 -DMI_ENABLE_AUTODIFF=1 -DNDEBUG \
        -I"$dir/mitsuba/include" -I"$dir/drjit/include" -I"$NB/include" -I"$NB/ext/robin_map/include" \
        -Itarget/cxxbridge -Itarget/inc
}
pids=()
for release in "${RELEASES[@]}"; do
    mkdir -p "$OBJ/$release"
    read -r -a release_flags <<<"$(flags "$release")"
    (g++ "${release_flags[@]}" -c cpp/plugin.cpp -o "$OBJ/$release/plugin.o" &&
        g++ "${release_flags[@]}" -c cpp/plugin_stub.cpp -o "$OBJ/$release/plugin_stub.o") &
    pids+=($!)
done
for pid in "${pids[@]}"; do wait "$pid"; done

# 4. The kernels once, exporting what the layers call: the symbols they leave undefined that
# the staticlib defines (the bridge's functions, the cxx runtime they use).
mkdir -p "$PKG/lib"
nm -u --format=posix "$OBJ"/*/plugin.o | awk '{print $1}' | sort -u >"$OBJ/needed.txt"
nm --defined-only --format=posix target/release/libmatte_plugin.a 2>/dev/null |
    awk 'NF >= 2 && $2 ~ /^[TWVDRB]$/ {print $1}' | sort -u >"$OBJ/defined.txt"
comm -12 "$OBJ/needed.txt" "$OBJ/defined.txt" >"$OBJ/exported.txt"
{ echo "{ global:"; sed 's/$/;/' "$OBJ/exported.txt"; echo "local: *; };"; } >"$OBJ/kernels.map"
# shellcheck disable=SC2046
g++ -shared -o "$PKG/lib/libmatte_kernels.so" $(sed 's/^/-Wl,--undefined=/' "$OBJ/exported.txt") \
    target/release/libmatte_plugin.a -Wl,--gc-sections -Wl,--version-script="$OBJ/kernels.map" -s \
    -Wl,-soname,libmatte_kernels.so -lpthread -ldl -lm

# 5. Each release's plugin folder: the layer and one stub per registered type (`matte types`).
rm -rf "$PKG/plugins" "$PKG/releases"   # plugins/: the single-release layout of earlier builds
for release in "${RELEASES[@]}"; do
    dir=$CACHE/$release
    out=$PKG/releases/$release/plugins
    mkdir -p "$out"
    g++ -shared -o "$out/libmatte_bsdfs.so" "$OBJ/$release/plugin.o" -L"$PKG/lib" -lmatte_kernels \
        -Wl,-rpath,'$ORIGIN/../../../lib' -Wl,--gc-sections -Wl,--version-script=cpp/exports.map -s \
        -L"$dir/mitsuba" -L"$dir/drjit" -lmitsuba -ldrjit-core -ldrjit-extra -lnanothread \
        -Wl,-z,defs -lpthread -ldl -lm
    for t in $(./target/release/matte types); do
        g++ -shared -o "$out/$t.so" "$OBJ/$release/plugin_stub.o" -Wl,--version-script=cpp/stub_exports.map -s \
            -L"$out" -lmatte_bsdfs -Wl,-rpath,'$ORIGIN'
    done
done

# 6. The releases built and the model registry (`matte types --json`) for matte_mitsuba.
printf '"""Generated by `cpp/build_plugin.sh`; do not edit (rerun it)."""\nMITSUBA_RELEASES = (%s)\nMODELS_JSON = r"""%s"""\n' \
    "$(printf '"%s", ' "${RELEASES[@]}")" "$(./target/release/matte types --json)" >"$PKG/_build.py"
echo "build_plugin: $PKG/lib/libmatte_kernels.so ($(du -k "$PKG/lib/libmatte_kernels.so" | cut -f1) KB) and a" \
    "layer per Mitsuba release ($(for r in "${RELEASES[@]}"; do printf '%s: %s KB; ' "$r" "$(du -k "$PKG/releases/$r/plugins/libmatte_bsdfs.so" | cut -f1)"; done | sed 's/; $//'))," \
    "plugins: $(./target/release/matte types | tr '\n' ' ')"
