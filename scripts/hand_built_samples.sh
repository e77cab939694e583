#!/usr/bin/env bash
# Sourced by the scripts that measure a model on a set of hand-built inputs (`sofa_pairs.sh`,
# `diners_at_tables.sh`): `hand_built_samples MODEL OUT INPUT_FILE…` copies the inputs into
# OUT/inputs (one folder: `generate` seeds an input by its place among the folder's inputs, by
# name, so a count is for this set of inputs), draws 8 samples of each (seed 3) with the default
# guidance and no repair into OUT/alone, repairs them into OUT/repaired, and prints how many of
# each input's samples pass `check` (physics, no stability) each way. Expects `$bin`.
hand_built_samples() {
    local model="$1" out="$2"
    shift 2
    rm -rf "$out"
    mkdir -p "$out/inputs"
    cp "$@" "$out/inputs/"
    $bin --no-progress -q generate --input "$out/inputs" --model "$model" --out "$out/alone" --samples 8 --seed 3 --no-repair
    $bin --no-progress -q repair "$out/alone" --out "$out/repaired"
    local run file name clean scene
    for run in alone repaired; do
        for file in "$@"; do
            name="$(basename "$file" .json)"
            clean=0
            for scene in "$out/$run/${name}"_*.json; do
                $bin -q check --no-stability "$scene" >/dev/null && clean=$((clean + 1))
            done
            echo "$run $name: $clean of 8 pass check"
        done
    done
}
