#!/usr/bin/env bash
# A dining model on the hand-built dining inputs and the demo's `dining_rect` (docs/RESULTS.md,
# "A hand on a table's end"): 8 samples per input (seed 3) with the default guidance and no
# repair, those samples repaired, how many pass `check` (physics, no stability) each way, and
# how many diners have their knees within 10 cm of a table's top (`examples/pair_gaps.rs`), per
# input alone and over all of them alone and repaired.
# The inputs go into one folder: `generate` seeds an input by its place among the folder's inputs
# (by name), so a count is for this set of inputs.
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
rm -rf "$out"
mkdir -p "$out/inputs"
for name in "${inputs[@]}"; do cp "tests/inputs/$name.json" "$out/inputs/"; done
cp scenes/examples/dining_rect.json "$out/inputs/"
inputs+=(dining_rect)
$bin --no-progress -q generate --input "$out/inputs" --model "$model" --out "$out/alone" --samples 8 --seed 3 --no-repair
$bin --no-progress -q repair "$out/alone" --out "$out/repaired"
for run in alone repaired; do
    for name in "${inputs[@]}"; do
        clean=0
        for scene in "$out/$run/${name}"_*.json; do
            $bin -q check --no-stability "$scene" >/dev/null && clean=$((clean + 1))
        done
        echo "$run $name: $clean of 8 pass check"
    done
done
for name in "${inputs[@]}"; do
    mkdir -p "$out/by_input/$name"
    cp "$out/alone/${name}"_*.json "$out/by_input/$name/"
    echo "alone $name: $($gaps "$out/by_input/$name" | grep '^diners')"
done
for run in alone repaired; do
    echo "$run, all inputs: $($gaps "$out/$run" | grep '^diners')"
done
