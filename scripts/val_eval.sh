#!/usr/bin/env bash
# A model on a validation split, as the experiments in docs/RESULTS.md are chosen: one sample per
# val input (seed SEED, default 0) with the default guidance and no repair (the model alone), those
# samples repaired as `generate` does by default, and `shade-sim eval` (with physics) of both
# against the val split itself, counts judged against DATA's train split and DATA-extra and
# DATA-extra2 and DATA-touch where they exist. Writes OUT/alone, OUT/repaired and OUT/eval.json; prints the table.
# Usage: bash scripts/val_eval.sh MODEL_DIR DATA_DIR OUT_DIR [SEED] [GENERATE_ARGS…]
#   e.g. bash scripts/val_eval.sh models/bedroom data/bedroom out/val/bedroom 0
#   GENERATE_ARGS go to `generate` as they are (`--eta 1.5 --eta-geometry-only`, `--guidance-config FILE`, `--expert DIR`).
set -euo pipefail
cd "$(dirname "$0")/.."
model="$1"
data="$2"
out="$3"
seed="${4:-0}"
cargo build --release --quiet
bin=./target/release/shade-sim
rm -rf "$out/alone" "$out/repaired"
mkdir -p "$out"
$bin --no-progress -q generate --input "$data/val" --model "$model" --out "$out/alone" --seed "$seed" \
    --no-repair "${@:5}"
$bin --no-progress -q repair "$out/alone" --out "$out/repaired"
extra=()
for draw in "$data-extra" "$data-extra2" "$data-touch"; do
    [ -d "$draw" ] && extra+=(--extra-data "$draw")
done
$bin --no-progress eval --pred "$out/alone" "$out/repaired" --ref "$data/val" "${extra[@]}" --out "$out/eval.json"
