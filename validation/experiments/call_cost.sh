#!/usr/bin/env bash
# Instructions per f32 eval and sample call (RGB) of each model, counted by callgrind over
# 20,000 calls (rust/brdf/examples/call_cost.rs): docs/performance.md#models-in-the-renderer.
#   validation/experiments/call_cost.sh [MODEL ...]     (default: lambert ginneken)
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release -q -p matte-brdf --example call_cost
bin=target/release/examples/call_cost
n=20000
models=("$@")
[ ${#models[@]} -gt 0 ] || models=(lambert ginneken)
for model in "${models[@]}"; do
    for what in eval sample; do
        total=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "--toggle-collect=call_cost::calls*" \
            "$bin" "$model" "$what" "$n" 2>&1 | awk '/Collected/ {print $4}')
        echo "$model $what $((total / n)) instructions per call"
    done
done
