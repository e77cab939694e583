#!/usr/bin/env bash
# The model card's test-split metrics: one sample per test input (seed 0) with the shipped models
# (embedded in the binary), unguided, with the three spatial terms (`all`) and with the default
# pipeline (`all` guidance and repair: the `all` samples repaired, which `shade-sim repair` reproduces exactly),
# and `shade-sim eval` (with physics) against the calibrated dataset (with DATA_DIR/<room>-extra and
# <room>-extra2 and <room>-touch, the further draws the model also trained on, as `--extra-data`
# where they exist).
# Usage: bash scripts/eval_models.sh [DATA_DIR] [OUT_DIR] [ROOMS…]   (defaults: data out/eval, all rooms)
set -euo pipefail
cd "$(dirname "$0")/.."
data="${1:-data}"
out="${2:-out/eval}"
rooms=("${@:3}")
[ ${#rooms[@]} -eq 0 ] && rooms=(bedroom living dining)
cargo build --release --quiet
bin=./target/release/shade-sim
for room in "${rooms[@]}"; do
    for guidance in none all; do
        rm -rf "$out/$room/$guidance"
        start=$(date +%s.%N)
        $bin --no-progress -q generate --input "$data/$room/test" --out "$out/$room/$guidance" --seed 0 --guidance "$guidance" --no-repair
        printf '%s %-4s: %d scenes in %.1f s\n' "$room" "$guidance" "$(ls "$out/$room/$guidance" | wc -l)" \
            "$(echo "$(date +%s.%N) - $start" | bc)" >&2
    done
    rm -rf "$out/$room/all+repair"
    $bin --no-progress -q repair "$out/$room/all" --out "$out/$room/all+repair"
    echo "## $room"
    # The further draws the model also trained on (models/MODEL_CARD.md) join the counts a real room has.
    extra=()
    for draw in "$data/$room-extra" "$data/$room-extra2" "$data/$room-touch"; do
        [ -d "$draw" ] && extra+=(--extra-data "$draw")
    done
    $bin --no-progress eval --pred "$out/$room/none" "$out/$room/all" "$out/$room/all+repair" --ref "$data/$room" \
        "${extra[@]}" --out "$out/$room.json"
done
