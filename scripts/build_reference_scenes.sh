#!/usr/bin/env bash
# Rebuilds the reference scenes and exports: scenes/reference/<example>.json are the example inputs
# furnished by the shipped models (guidance all and repair, seed 0, one sample each, the folder in
# one run: the rooms `shade-sim demo` writes as out/demo/<example>_0.json), and mjcf/ holds
# their MJCF exports, which are also the expected outputs of the snapshot test
# `export::reference_exports_match_the_snapshots`. Run after a change to the models or the export.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p scenes/reference
./target/release/shade-sim -q generate --input scenes/examples --out "$tmp" --samples 1 --seed 0
for input in scenes/examples/*.json; do
    name=$(basename "$input" .json)
    mv "$tmp/${name}_0.json" "scenes/reference/$name.json"
done
INSTA_UPDATE=always INSTA_FORCE_PASS=1 cargo test --quiet --test it -- export::reference_exports_match_the_snapshots
ls -l scenes/reference mjcf
