#!/usr/bin/env bash
# The model card's test-split metrics: one sample per test input with the shipped models (embedded
# in the binary) and `shade-sim eval` against the calibrated dataset.
# Usage: bash scripts/eval_models.sh [DATA_DIR] [OUT_DIR] [extra generate flags…]
set -euo pipefail
cd "$(dirname "$0")/.."
data="${1:-data}"
out="${2:-out/eval}"
shift 2 || true
cargo build --release --quiet
bin=./target/release/shade-sim
for room in bedroom living dining; do
    rm -rf "$out/$room"
    start=$(date +%s.%N)
    $bin --no-progress -q generate --input "$data/$room/test" --out "$out/$room" --seed 0 "$@"
    end=$(date +%s.%N)
    printf '%s: generated %d scenes in %.1f s\n' "$room" "$(ls "$out/$room" | wc -l)" "$(echo "$end - $start" | bc)"
    $bin --no-progress eval --pred "$out/$room" --ref "$data/$room" --out "$out/$room.json"
done
