#!/usr/bin/env bash
# Reproduces the shipped models (models/MODEL_CARD.md): the calibrated datasets at SHADE's sizes,
# then the three trainings of 24,000 steps with rare categories weighed up (--category-balance: 0.5
# for bedrooms, 0.25 for living and dining rooms, where 0.5 oversampled them),
# one thread each (as fast per run as two threads on this 2-core machine): about 50 minutes for one
# alone, about 80 minutes for the three side by side on a 2-core machine.
# Usage: bash scripts/train_models.sh [DATA_DIR] [MODELS_DIR]   (defaults: data, models)
set -euo pipefail
cd "$(dirname "$0")/.."
data="${1:-data}"
models="${2:-models}"
cargo build --release --quiet
bin=./target/release/shade-sim
for spec in bedroom:5689 living:2987 dining:2549; do
    room="${spec%%:*}"; n="${spec##*:}"
    [ -f "$data/$room/stats.json" ] && continue
    $bin --no-progress -q synth --room "$room" --scenes "$n" --seed 0 --out "$data/$room-raw"
    $bin --no-progress -q calibrate --data "$data/$room-raw" --out "$data/$room"
done
train() {
    local room="$1" steps="$2" balance="$3" resume=()
    [ -f "$models/$room/train_state.json" ] && resume=(--resume)
    RAYON_NUM_THREADS=1 $bin --no-progress train --data "$data/$room" --out "$models/$room" --steps "$steps" \
        --category-balance "$balance" "${resume[@]}"
}
train bedroom 24000 0.5 &
first=$!
train dining 24000 0.25 &
second=$!
train living 24000 0.25
wait "$first" "$second"
