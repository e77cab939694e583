#!/usr/bin/env bash
# Reproduces the shipped models (models/MODEL_CARD.md): the clean calibrated datasets at SHADE's
# sizes (`--require-clean`: every room passes `check`), second draws of 13,650 bedrooms, 8,961
# living rooms and 7,647 dining rooms (seed 1) and thirds of 27,300 bedrooms, 17,922 living
# rooms and 20,000 dining rooms (seed 2; a person's hand on a table at any of its sides,
# `synth --touch-any-side`) that join their training splits (`--extra-data`; val and test stay
# the first draw's), then the three trainings with rare categories weighed up
# (--category-balance 0.25), one after another, each on every core: bedrooms 240,000 steps
# (about 112 minutes alone on a 2-core machine, plus 13 for the extra rooms), living rooms 200,000
# (about 134, plus 12), dining rooms 170,000 (about 126, plus 15).
# Usage: bash scripts/train_models.sh [DATA_DIR] [MODELS_DIR]   (defaults: data, models)
set -euo pipefail
cd "$(dirname "$0")/.."
data="${1:-data}"
models="${2:-models}"
cargo build --release --quiet
# The shipped models were trained on data calibrated before calibration kept people out of each
# other (docs/RESULTS.md, "People inside each other in the data"): the flag makes it as it was.
overlap=(--people-may-overlap)
bin=./target/release/shade-sim
for spec in bedroom:5689 living:2987 dining:2549; do
    room="${spec%%:*}"; n="${spec##*:}"
    [ -f "$data/$room/stats.json" ] && continue
    $bin --no-progress -q synth --room "$room" --scenes "$n" --seed 0 --out "$data/$room-raw" --require-clean
    $bin --no-progress -q calibrate --data "$data/$room-raw" --out "$data/$room" --require-clean "${overlap[@]}"
done
# DRAW:ROOM:SCENES:SEED[:SYNTH_FLAG]: more rooms of ROOM, drawn with SEED, in DATA_DIR/ROOM-DRAW.
# The dining rooms' third draw lets a person touching a table stand at any of its sides (`synth
# --touch-any-side`; docs/RESULTS.md, "A hand on a table's end").
for spec in extra:bedroom:13650:1 extra:living:8961:1 extra:dining:7647:1 extra2:bedroom:27300:2 extra2:living:17922:2 touch:dining:20000:2:--touch-any-side; do
    IFS=: read -r draw room n seed flag <<< "$spec"
    [ -f "$data/$room-$draw/stats.json" ] && continue
    $bin --no-progress -q synth --room "$room" --scenes "$n" --seed "$seed" --out "$data/$room-$draw-raw" --require-clean ${flag:+"$flag"}
    $bin --no-progress -q calibrate --data "$data/$room-$draw-raw" --out "$data/$room-$draw" --require-clean "${overlap[@]}"
done
# train ROOM[:FOLDER] STEPS BALANCE ARGS…: ROOM's data, the model written to models/FOLDER (ROOM's own by default).
train() {
    local room="${1%%:*}" folder="${1##*:}" steps="$2" balance="$3" resume=()
    [ -f "$models/$folder/train_state.json" ] && resume=(--resume)
    $bin --no-progress train --data "$data/$room" --out "$models/$folder" --steps "$steps" \
        --category-balance "$balance" "${resume[@]}" "${@:4}"
}
# Ten times the rooms: the 4,551 of the first draw alone overfit by 36,000 steps, and with them
# B 0.5 drew rare categories at 2–6× their share (docs/RESULTS.md, "Four ways to a more precise
# bedroom model"); 2.5 times the rooms and steps of the model before (docs/RESULTS.md, "Ten times
# the rooms"), then twice the steps on them (docs/RESULTS.md, "The bedroom model for 240,000 steps").
# v-prediction on the log-SNR schedule with Min-SNR-5 floored at 1 (docs/RESULTS.md, "A floor under
# Min-SNR"). A peak learning rate of 1e-3 instead of 3e-4: the same validation loss, rooms the judge
# finds more real (docs/RESULTS.md, "The bedroom model at a peak of 1e-3").
train bedroom 240000 0.25 --extra-data "$data/bedroom-extra" --extra-data "$data/bedroom-extra2" \
    --prediction v --schedule log_snr --min-snr 5 --min-snr-floor 1 --lr 1e-3
# Living and dining rooms keep the earlier preset's yaw and no wall distances: the new preset
# scored worse on their val splits (docs/RESULTS.md). The living model is the bedrooms' v model
# on 29,273 rooms for 200,000 steps; it replaced an x0 model that needed a low-noise expert for
# its last steps (docs/RESULTS.md, "The living model as a v model"), and samples with DDIM's
# eta 2 on the geometry (chosen on val; recorded in its config.json; docs/RESULTS.md, "The living
# model's geometry at η 2").
# A peak learning rate of 1e-3, as the bedrooms': val SCA 0.035 / 0.029 lower over three seeds
# (docs/RESULTS.md, "The living model at a peak of 1e-3").
train living 200000 0.25 --extra-data "$data/living-extra" --extra-data "$data/living-extra2" \
    --anchored-yaw box --wall-features false \
    --prediction v --schedule log_snr --min-snr 5 --min-snr-floor 1 --geometry-eta 2 --lr 1e-3
# Dining: the v model of the bedrooms (docs/RESULTS.md, "The dining v model on both draws").
# Its default sampler, DDIM's eta 2 on the geometry (docs/RESULTS.md, "Fresh noise on the dining
# rooms' geometry", then "The dining model's geometry at η 2"), goes into its config.json.
# 29,686 rooms for 170,000 steps, most of the 150 minutes the model issue allows
# (docs/RESULTS.md, "The dining model for 170,000 steps").
train dining 170000 0.25 --extra-data "$data/dining-extra" --extra-data "$data/dining-touch" \
    --anchored-yaw box --wall-features false \
    --prediction v --schedule log_snr --min-snr 5 --min-snr-floor 1 --geometry-eta 2
