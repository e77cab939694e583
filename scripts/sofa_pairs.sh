#!/usr/bin/env bash
# A living model on the hand-built inputs with people side by side (docs/RESULTS.md, "Sofas that
# stand out in the room"): 8 samples per input (seed 3) with the default guidance and no repair,
# those samples repaired, how many pass `check` (physics, no stability) each way, and what the
# sitters sit on (`examples/seats_of_sitters.rs`: the side-by-side pairs that share one sofa).
# The inputs share one folder, so a count is for this set of inputs (`hand_built_samples.sh`).
# Usage: bash scripts/sofa_pairs.sh MODEL_DIR OUT_DIR   (e.g. models/living out/pairs/shipped)
set -euo pipefail
cd "$(dirname "$0")/.."
model="$1"
out="$2"
cargo build --release --quiet --bin shade-sim --example seats_of_sitters
bin=./target/release/shade-sim
inputs=(l_living_pair_and_walker living_at_an_angle open_plan_sofa_and_table three_on_a_sofa
    sofa_pair_a_metre_off_the_wall sofa_pair_in_the_open sofa_pair_walker_behind)
inputs=("${inputs[@]/%/.json}")
source scripts/hand_built_samples.sh
hand_built_samples "$model" "$out" "${inputs[@]/#/tests/inputs/}"
./target/release/examples/seats_of_sitters "$out/alone" "$out/repaired" | grep -v '^    '
