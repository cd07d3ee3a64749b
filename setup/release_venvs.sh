#!/usr/bin/env bash
# The environments of the Mitsuba release matrix (tests/plugin/test_releases.py): for each
# release of cpp/mitsuba_releases.txt, <repo>/.venvs/mitsuba-<release> with that Mitsuba (and
# the Dr.Jit it pins) and the numpy of setup/requirements.txt, created once and
# reused; then the wheel given (default: this machine's manylinux wheel of `make dist`) installed into each
# without its dependencies, as a user adds matte to an environment that has Mitsuba. Also
# .venvs/mitsuba-3.6.4, the release before the oldest supported one, where the import must fail.
#     setup/release_venvs.sh [WHEEL]
#     setup/release_venvs.sh --environments    (only make the environments: no wheel needed)
# Prints one line saying what it did. Safe to run any number of times.
set -euo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# One at a time: pytest's workers (make test runs it with -n 2) may reach here together.
mkdir -p .venvs
exec 9>.venvs/.lock
flock 9

WHEEL=
if [ "${1:-}" != --environments ]; then
    WHEEL=${1:-$(ls dist/matte_mitsuba-*manylinux*_"$(uname -m)".whl 2>/dev/null | head -1)}
    [ -f "$WHEEL" ] || { echo "release_venvs: no wheel (run make dist, or name one)" >&2; exit 1; }
fi
NUMPY=$(grep '^numpy==' setup/requirements.txt)
created=()
for release in $(grep -v '^#' cpp/mitsuba_releases.txt | awk 'NF {print $1}') 3.6.4; do
    venv=.venvs/mitsuba-$release
    stamp=$venv/.matte-release
    if [ "$(cat "$stamp" 2>/dev/null)" != "mitsuba==$release $NUMPY" ]; then
        rm -rf "$venv"
        python3 -m venv "$venv"
        "$venv/bin/python" -m pip install -q --disable-pip-version-check "mitsuba==$release" "$NUMPY"
        echo "mitsuba==$release $NUMPY" >"$stamp"
        created+=("$release")
    fi
    if [ -n "$WHEEL" ]; then
        "$venv/bin/python" -m pip install -q --disable-pip-version-check --no-deps --force-reinstall "$WHEEL"
    fi
done
if [ -n "$WHEEL" ]; then
    echo "release_venvs: $(basename "$WHEEL") installed into .venvs/mitsuba-*${created:+ (created for ${created[*]})}"
else
    echo "release_venvs: .venvs/mitsuba-* ${created:+created for ${created[*]}}${created:-up to date}"
fi
