#!/usr/bin/env bash
# SHADE's Table 3 on the calibrated synthetic test splits: the shipped models sampled with
# none / +motion / +boundary / +object / all / all+phys guidance (one sample per test input, seed 0),
# then all+repair and all+phys+repair (the default is sampling with `all` and repairing:
# `shade-sim repair` on those folders gives the same files, tests/it/model.rs checks it), each folder
# a row of `shade-sim eval` (Col_mot, R_out, Col_obj, contact IoU, physics rates, and the mean of
# the three layout metrics each over the unguided row's).
# Usage: bash scripts/ablation.sh [DATA_DIR] [OUT_DIR] [ROOMS…]   (defaults: data out/ablation, all rooms)
set -euo pipefail
cd "$(dirname "$0")/.."
data="${1:-data}"
out="${2:-out/ablation}"
shift 2 || true
rooms=("$@")
[ ${#rooms[@]} -eq 0 ] && rooms=(bedroom living dining)
cargo build --release --quiet
bin=./target/release/shade-sim
for room in "${rooms[@]}"; do
    dirs=()
    for spec in none:none mot:mot bound:bound obj:obj all:all all+phys:all,phys; do
        name="${spec%%:*}"; terms="${spec##*:}"
        rm -rf "$out/$room/$name"
        start=$(date +%s.%N)
        $bin --no-progress -q generate --input "$data/$room/test" --out "$out/$room/$name" --seed 0 --guidance "$terms" --no-repair
        printf '%s %-9s %6.1f s\n' "$room" "$name" "$(echo "$(date +%s.%N) - $start" | bc)" >&2
        dirs+=("$out/$room/$name")
    done
    for name in all all+phys; do
        rm -rf "$out/$room/$name+repair"
        $bin --no-progress -q repair "$out/$room/$name" --out "$out/$room/$name+repair"
        dirs+=("$out/$room/$name+repair")
    done
    echo "## $room"
    $bin --no-progress eval --pred "${dirs[@]}" --ref "$data/$room" --out "$out/$room.json" --baseline none
done
