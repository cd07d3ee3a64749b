# What the setup scripts share (sourced after their `set -euo pipefail`): a failure names the
# script, line and command instead of ending it silently, and `quiet` runs a command showing
# its output only if it fails.
# shellcheck shell=bash
trap '[[ $BASH_COMMAND == return* ]] || echo "${0##*/}: line $LINENO: \`$BASH_COMMAND\` failed" >&2' ERR

quiet() {
    local log rc=0
    log=$(mktemp)
    "$@" >"$log" 2>&1 || rc=$?
    if [ "$rc" -ne 0 ]; then
        echo "${0##*/}: line ${BASH_LINENO[0]}: \`$*\` failed (exit $rc):" >&2
        cat "$log" >&2
    fi
    rm -f "$log"
    return "$rc"
}
