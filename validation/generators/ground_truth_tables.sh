#!/usr/bin/env bash
# The ground-truth tables in python/matte_mitsuba/ground_truth/ (docs/microgeometry.md#the-tabulated-ground-truth-brdf):
# V-cavities σ and Gaussian height fields m at each roughness below, all bounces, fixed seeds and
# photon counts. Prints each table's report (largest E/ρ before matching, half-widths, white
# albedo) and its wall time.
#
#     validation/generators/ground_truth_tables.sh [OUT_DIR]     # `make ground-truth`; MATTE=path overrides the binary
set -euo pipefail
MATTE=${MATTE:-target/release/matte}
OUT=${1:-python/matte_mitsuba/ground_truth}
ROUGHNESS="0.1 0.2 0.3 0.5 0.7 1.0"   # also in tests/kernels/ground_truth_tables.rs (12 files: tests/plugin/wheel_checks.py)
VC_PHOTONS=2000000 VC_SEED=5                          # per θi node
HF_PHOTONS=96000 HF_SEED=6 HF_CELLS=256 HF_REALISATIONS=8  # per θi node, split over the realisations
mkdir -p "$OUT"
run() {
    local file=$1; shift
    local start=$SECONDS
    echo "== $file"
    "$MATTE" microgeometry "$@" --table "$OUT/$file"
    echo "== $file: $((SECONDS - start)) s, $(wc -c < "$OUT/$file") bytes"
}
for s in $ROUGHNESS; do
    run "v_cavities_sigma$s.json" --surface v-cavities --roughness "$s" --photons $VC_PHOTONS --seed $VC_SEED
done
for s in $ROUGHNESS; do
    run "height_field_m$s.json" --surface height-field --roughness "$s" --cells $HF_CELLS \
        --realisations $HF_REALISATIONS --photons $HF_PHOTONS --seed $HF_SEED
done
