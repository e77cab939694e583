#!/usr/bin/env bash
# Times `shade-sim synth` at the SHADE paper's full dataset sizes (5,689 bedrooms, 2,987 living
# rooms, 2,549 dining rooms) and prints the seconds per room type and in total.
# Usage: bash scripts/synth_full_timing.sh [OUT_DIR]   (default: a temporary folder, removed after)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
out="${1:-$(mktemp -d)}"
total_start=$(date +%s.%N)
for spec in bedroom:5689 living:2987 dining:2549; do
    room="${spec%%:*}"; n="${spec##*:}"
    start=$(date +%s.%N)
    ./target/release/shade-sim --no-progress -q synth --room "$room" --scenes "$n" --seed 0 --out "$out/$room"
    end=$(date +%s.%N)
    printf '%-8s %5d rooms  %6.1f s  (%d files)\n' "$room" "$n" "$(echo "$end - $start" | bc)" "$(find "$out/$room" -name '*.json' | wc -l)"
done
total_end=$(date +%s.%N)
printf 'total    %5d rooms  %6.1f s  (target: under 120 s)\n' 11225 "$(echo "$total_end - $total_start" | bc)"
du -sh "$out" | awk '{print "on disk: " $1}'
[ -z "${1:-}" ] && rm -rf "$out"
