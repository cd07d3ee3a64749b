#!/usr/bin/env bash
# The emulated Linux aarch64 environments of the aarch64 wheel's checks
# (tests/plugin/test_aarch64.py), on an x86-64 machine:
#   1. Debian's qemu-user-static, which runs aarch64 executables here;
#   2. a sysroot: Debian's arm64 Python 3.11 and libLLVM 19 (Dr.Jit's llvm variants load it)
#      with every arm64 library they depend on, unpacked with `dpkg -x` (nothing is installed
#      for arm64 on this machine), and a /proc/cpuinfo of an aarch64 CPU inside it (qemu-user
#      shows the host's, whose flags make Dr.Jit's LLVM backend refuse: "no suitable vector
#      ISA"; qemu opens absolute paths under the sysroot first);
#   3. per release given: a site folder with that release's aarch64 mitsuba, drjit and the numpy
#      of requirements.txt (pip --target --platform manylinux2014_aarch64), then the wheel given
#      installed into it without its dependencies;
#   4. bin/python-<release>: a script that runs the sysroot's Python under qemu with that site
#      folder, and bin/qemu: qemu with the sysroot, for the aarch64 `matte` binary.
# Made once in $MATTE_MITSUBA_CACHE/linux-aarch64-env (default ~/.cache/matte-mitsuba/…) and
# reused; the wheel is installed anew each call. Prints the environment's folder.
#     setup/aarch64_env.sh WHEEL RELEASE...
set -euo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cd "$(dirname "${BASH_SOURCE[0]}")/.."

WHEEL=$(realpath "$1")
shift
CACHE=${MATTE_MITSUBA_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/matte-mitsuba}
ENV=$CACHE/linux-aarch64-env
SYSROOT=$ENV/sysroot
NUMPY=$(grep '^numpy==' setup/requirements.txt)
# What Python and libLLVM need of Debian's arm64 packages, resolved by apt (see below).
ROOTS="python3.11-minimal libpython3.11-stdlib libllvm19 libstdc++6 libgcc-s1 libatomic1"
QEMU=/usr/bin/qemu-aarch64-static

# --- 1. qemu ---------------------------------------------------------------------------------
if [ ! -x "$QEMU" ]; then
    quiet apt-get update -q
    quiet env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends qemu-user-static
fi

# --- 2. the sysroot --------------------------------------------------------------------------
if [ "$(cat "$SYSROOT/.complete" 2>/dev/null)" != "$ROOTS" ]; then
    rm -rf "$SYSROOT"
    mkdir -p "$SYSROOT"
    if ! dpkg --print-foreign-architectures | grep -qx arm64; then
        dpkg --add-architecture arm64
    fi
    # (None before apt has fetched the arm64 lists: an empty answer, not a failure.)
    apt_depends() {
        # shellcheck disable=SC2046
        apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts --no-breaks \
            --no-replaces --no-enhances --no-pre-depends $(printf '%s:arm64 ' $ROOTS) 2>/dev/null |
            grep -E '^[a-z0-9.+-]+:arm64$' | grep -vE '^(dpkg|tar|install-info|gcc-12-base):' | sort -u || true
    }
    packages=$(apt_depends)
    if ! grep -qx 'libllvm19:arm64' <<<"$packages"; then
        quiet apt-get update -q
        packages=$(apt_depends)
    fi
    debs=$(mktemp -d)
    # shellcheck disable=SC2086
    (cd "$debs" && quiet apt-get download $packages) ||
        { echo "aarch64_env: could not download Debian's arm64 packages: $(echo $packages)" >&2; exit 1; }
    for deb in "$debs"/*.deb; do dpkg -x "$deb" "$SYSROOT"; done
    rm -rf "$debs"
    mkdir -p "$SYSROOT/proc"
    cat >"$SYSROOT/proc/cpuinfo" <<'EOF'
processor	: 0
BogoMIPS	: 50.00
Features	: fp asimd evtstrm aes pmull sha1 sha2 crc32 atomics fphp asimdhp cpuid asimdrdm lrcpc dcpop asimddp
CPU implementer	: 0x41
CPU architecture: 8
CPU variant	: 0x3
CPU part	: 0xd0c
CPU revision	: 1

EOF
    echo "$ROOTS" >"$SYSROOT/.complete"
fi
LLVM=$(ls "$SYSROOT"/usr/lib/aarch64-linux-gnu/libLLVM.so.19* | head -1)

# --- 3. and 4. per release -------------------------------------------------------------------
mkdir -p "$ENV/bin"
cat >"$ENV/bin/qemu" <<EOF
#!/bin/sh
# Runs an aarch64 executable of this machine under qemu, with the aarch64 sysroot.
exec $QEMU -L "$SYSROOT" "\$@"
EOF
chmod +x "$ENV/bin/qemu"
for release in "$@"; do
    site=$ENV/site-$release
    stamp=$site/.matte-release
    if [ "$(cat "$stamp" 2>/dev/null)" != "mitsuba==$release $NUMPY" ]; then
        rm -rf "$site"
        quiet python3 -m pip install -q --disable-pip-version-check --target "$site" --only-binary=:all: \
            --python-version 3.11 --implementation cp --abi cp311 --platform manylinux2014_aarch64 \
            --platform manylinux_2_17_aarch64 --platform manylinux_2_28_aarch64 "mitsuba==$release" "$NUMPY"
        echo "mitsuba==$release $NUMPY" >"$stamp"
    fi
    rm -rf "$site"/matte_mitsuba "$site"/matte_mitsuba-*.dist-info
    quiet python3 -m pip install -q --disable-pip-version-check --target "$site" --no-deps --only-binary=:all: \
        --python-version 3.11 --implementation cp --abi cp311 --platform "$(basename "$WHEEL" .whl | sed 's/.*-//')" \
        --upgrade "$WHEEL"
    cat >"$ENV/bin/python-$release" <<EOF
#!/bin/sh
# The sysroot's aarch64 Python 3.11 under qemu, with Mitsuba $release and matte's aarch64 wheel.
export PYTHONPATH="$site" DRJIT_LIBLLVM_PATH="$LLVM"
exec $QEMU -L "$SYSROOT" "$SYSROOT/usr/bin/python3.11" "\$@"
EOF
    chmod +x "$ENV/bin/python-$release"
done
echo "$ENV"
