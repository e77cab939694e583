#!/usr/bin/env bash
# A dining model on the hand-built dining inputs and the demo's `dining_rect` (docs/RESULTS.md,
# "A hand on a table's end"): 8 samples per input (seed 3) with the default guidance and no
# repair, those samples repaired, how many pass `check` (physics, no stability) each way, and
# how many diners have their knees within 10 cm of a table's top (`examples/pair_gaps.rs`), per
# input alone and over all of them alone and repaired.
# The inputs share one folder, so a count is for this set of inputs (`hand_built_samples.sh`).
# Usage: bash scripts/diners_at_tables.sh MODEL_DIR OUT_DIR   (e.g. models/dining out/diners/shipped)
set -euo pipefail
cd "$(dirname "$0")/.."
model="$1"
out="$2"
cargo build --release --quiet --bin shade-sim --example pair_gaps
bin=./target/release/shade-sim
gaps=./target/release/examples/pair_gaps
inputs=(dining_hand_at_the_head dining_four_walker_behind dinner_for_three l_dining_six dining_square_four
    dining_for_two_narrow)
files=("${inputs[@]/#/tests/inputs/}")
files=("${files[@]/%/.json}" scenes/examples/dining_rect.json)
inputs+=(dining_rect)
source scripts/hand_built_samples.sh
hand_built_samples "$model" "$out" "${files[@]}"
for name in "${inputs[@]}"; do
    mkdir -p "$out/by_input/$name"
    cp "$out/alone/${name}"_*.json "$out/by_input/$name/"
    echo "alone $name: $($gaps "$out/by_input/$name" | grep '^diners')"
done
for run in alone repaired; do
    echo "$run, all inputs: $($gaps "$out/$run" | grep '^diners')"
done
