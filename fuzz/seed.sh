#!/usr/bin/env bash
# Seed corpora for the fuzz targets from the repo's own files: every scene under scenes/ and
# tests/inputs for `scene`; each shipped model's config.json (on one line) with and without its
# weights for `checkpoint`; the shipped BVH clips (first byte 0: the BVH reader) for `motion`.
set -euo pipefail
cd "$(dirname "$0")"
mkdir -p corpus/scene corpus/checkpoint corpus/motion
for f in ../scenes/*/*.json ../tests/inputs/*.json; do
    cp "$f" "corpus/scene/$(basename "$(dirname "$f")")_$(basename "$f")"
done
for room in bedroom living dining; do
    python3 -c 'import json,sys; print(json.dumps(json.load(open(sys.argv[1]))))' "../models/$room/config.json" \
        > "corpus/checkpoint/${room}_config"
    cat "corpus/checkpoint/${room}_config" "../models/$room/model.safetensors" > "corpus/checkpoint/${room}_model"
done
for f in ../scenes/motion/*.bvh; do
    { printf '\0'; cat "$f"; } > "corpus/motion/$(basename "$f")"
done
