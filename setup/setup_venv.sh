#!/usr/bin/env bash
# Idempotent set-up of matte's Python side and run-time libraries:
#   1. the Debian packages libllvm19 (Dr.Jit's llvm_* variants load it at run
#      time; LLVM 15, which Debian 12 also ships, makes Dr.Jit 1.5.0 abort) and
#      libembree3-3 (Embree 3.13; matte's renderer loads libembree3.so.3 at run
#      time for its ray queries, rust/render/src/accel/embree_api.rs, and falls back
#      to its own BVH without it), and clang-format (`make test` checks cpp/'s style);
#      for the Linux aarch64 wheel (`make dist`), the cross compiler g++-aarch64-linux-gnu, Rust's
#      aarch64-unknown-linux-gnu target, and qemu-user-static, which runs it under emulation
#      (tests/plugin/test_aarch64.py); for the macOS arm64 wheel, Rust's aarch64-apple-darwin
#      target (Zig, the C++ compiler and linker, comes from PyPI with the venv);
#   2. <repo>/.venv with setup/requirements.txt installed, re-installed
#      only when that file changed since the last successful install.
# matte_mitsuba itself is installed into the venv as the wheel `make plugin` builds.
# Prints one line saying what it did. Safe to run from anywhere, any number of times.
set -euo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/common.sh"

cd "$(dirname "${BASH_SOURCE[0]}")/.."

LIBLLVM=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1   # provided by libllvm19
LIBEMBREE=/usr/lib/x86_64-linux-gnu/libembree3.so.3 # provided by libembree3-3
CLANG_FORMAT=/usr/bin/clang-format                  # provided by clang-format (`make test` checks cpp/)
CROSS_CXX=/usr/bin/aarch64-linux-gnu-g++            # provided by g++-aarch64-linux-gnu
QEMU=/usr/bin/qemu-aarch64-static                   # provided by qemu-user-static
RUST_TARGETS=(aarch64-unknown-linux-gnu aarch64-apple-darwin)  # the cross-built wheels' Rust targets
VENV=.venv
REQ=setup/requirements.txt
STAMP="$VENV/.matte-requirements.sha256"
did=()


# --- 1. libLLVM 19 and Embree 3 ----------------------------------------------
packages=()
[ -e "$LIBLLVM" ] || packages+=(libllvm19)
[ -e "$LIBEMBREE" ] || packages+=(libembree3-3)
[ -e "$CLANG_FORMAT" ] || packages+=(clang-format)
[ -e "$CROSS_CXX" ] || packages+=(g++-aarch64-linux-gnu)
[ -e "$QEMU" ] || packages+=(qemu-user-static)
if [ ${#packages[@]} -gt 0 ]; then
    SUDO=()
    if [ "$(id -u)" -ne 0 ]; then SUDO=(sudo); fi
    apt_install() {
        "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive \
            apt-get install -y -q --no-install-recommends "${packages[@]}"
    }
    # Try without refreshing the package lists first; update only if needed.
    if ! apt_install >/dev/null 2>&1; then
        quiet "${SUDO[@]}" apt-get update -q
        quiet apt_install
    fi
    [ -e "$LIBLLVM" ] || { echo "setup_venv: libllvm19 installed but $LIBLLVM is missing" >&2; exit 1; }
    [ -e "$LIBEMBREE" ] || { echo "setup_venv: libembree3-3 installed but $LIBEMBREE is missing" >&2; exit 1; }
    [ -e "$CLANG_FORMAT" ] || { echo "setup_venv: clang-format installed but $CLANG_FORMAT is missing" >&2; exit 1; }
    [ -e "$CROSS_CXX" ] || { echo "setup_venv: g++-aarch64-linux-gnu installed but $CROSS_CXX is missing" >&2; exit 1; }
    [ -e "$QEMU" ] || { echo "setup_venv: qemu-user-static installed but $QEMU is missing" >&2; exit 1; }
    did+=("installed ${packages[*]}")
fi

for target in "${RUST_TARGETS[@]}"; do
    if ! rustup target list --installed 2>/dev/null | grep -qx "$target"; then
        quiet rustup target add "$target" ||
            { echo "setup_venv: rustup could not add Rust's $target target, which a cross-built wheel needs (rustup target add $target)" >&2; exit 1; }
        did+=("added Rust's $target target")
    fi
done

# --- 2. virtualenv -----------------------------------------------------------
if [ ! -x "$VENV/bin/python" ] || ! "$VENV/bin/python" -c '' 2>/dev/null; then
    rm -rf "$VENV"
    python3 -m venv "$VENV"
    did+=("created $VENV")
fi

# --- 3. requirements ---------------------------------------------------------
want=$( { sha256sum "$REQ" | cut -d' ' -f1; "$VENV/bin/python" -c 'import sys; print(sys.version)'; } | sha256sum | cut -d' ' -f1)
have=$(cat "$STAMP" 2>/dev/null || true)
if [ "$want" != "$have" ]; then
    "$VENV/bin/python" -m pip install -q --disable-pip-version-check -r "$REQ"
    echo "$want" >"$STAMP"
    did+=("installed $REQ")
fi

# --- 4. no path into the checkout: matte_mitsuba comes from the wheel (`make plugin`) ---
PTH="$("$VENV/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')/matte.pth"
if [ -e "$PTH" ]; then
    rm -f "$PTH"
    did+=("removed the old matte.pth (matte_mitsuba is installed from the wheel now)")
fi

if [ ${#did[@]} -eq 0 ]; then
    echo "setup_venv: up to date (libllvm19, libembree3-3, clang-format, the aarch64 cross toolchain, qemu and Rust's cross targets present, $VENV matches $REQ)"
else
    msg=$(IFS=';'; echo "${did[*]}")
    echo "setup_venv: ${msg//;/, }"
fi
