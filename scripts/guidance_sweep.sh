#!/usr/bin/env bash
# Picks the guidance step size γ: the first 64 scenes of each room's val split, sampled with all
# spatial terms at several γ (seed 0), evaluated without physics. The choice is recorded in
# docs/RESULTS.md. Usage: bash scripts/guidance_sweep.sh [DATA_DIR] [OUT_DIR] [ROOMS…]
set -euo pipefail
cd "$(dirname "$0")/.."
data="${1:-data}"
out="${2:-out/sweep}"
cargo build --release --quiet
bin=./target/release/shade-sim
rooms=("${@:3}")
[ ${#rooms[@]} -eq 0 ] && rooms=(bedroom living dining)
for room in "${rooms[@]}"; do
    inputs="$out/$room/inputs"
    rm -rf "$out/$room"; mkdir -p "$inputs"
    for f in $(ls "$data/$room/val" | head -64); do ln -s "$(realpath "$data/$room/val/$f")" "$inputs/$f"; done
    dirs=()
    for scale in 0 0.02 0.05 0.1 0.2 0.4; do
        $bin --no-progress -q generate --input "$inputs" --out "$out/$room/gamma-$scale" --seed 0 --guidance all --guidance-scale "$scale"
        dirs+=("$out/$room/gamma-$scale")
    done
    echo "## $room"
    $bin --no-progress eval --no-physics --pred "${dirs[@]}" --ref "$data/$room"
done
