#!/usr/bin/env bash
# What each repair step is worth: the val split's inputs sampled once with the shipped models
# (`all` guidance, no repair, seed 0), then repaired by the full pipeline and by the pipeline with
# each step switched off in turn (a config without it, `shade-sim repair --config`), and by settle
# without each of its parts (completion, squaring, walls), every folder a
# row of `shade-sim eval` against the val split; prints a Markdown table (rooms failing `check`,
# contact IoU, Col_mot, CKL, the rooms each step's absence costs, and how many rooms' layouts it
# changes at all) and writes OUT_DIR/<room>.json.
# Usage: bash scripts/repair_ablation.sh [DATA_DIR] [OUT_DIR] [LIMIT] [ROOMS…]
#   LIMIT: only the first LIMIT val inputs of each room (0 = all, the default).
set -euo pipefail
cd "$(dirname "$0")/.."
data="${1:-data}"
out="${2:-out/repair_ablation}"
limit="${3:-0}"
rooms=("${@:4}")
[ ${#rooms[@]} -eq 0 ] && rooms=(bedroom living dining)
cargo build --release --quiet
bin=./target/release/shade-sim
steps=$($bin repair --print-config | python3 -c 'import json, sys; print(" ".join(json.load(sys.stdin)["steps"]))')
for room in "${rooms[@]}"; do
    base="$out/$room"
    rm -rf "$base" && mkdir -p "$base/inputs" "$base/configs"
    files=$(ls "$data/$room/val"/*.json | sort)
    [ "$limit" -gt 0 ] && files=$(echo "$files" | sed -n "1,${limit}p")
    for f in $files; do cp "$f" "$base/inputs/"; done
    $bin --no-progress -q generate --input "$base/inputs" --out "$base/sampled" --seed 0 --guidance all --no-repair
    $bin --no-progress -q repair "$base/sampled" --out "$base/all"
    dirs=("$base/sampled" "$base/all")
    for step in $steps; do
        python3 -c 'import json, sys; s = sys.argv[1].split(); print(json.dumps({"steps": [x for x in s if x != sys.argv[2]]}))' \
            "$steps" "$step" > "$base/configs/without_$step.json"
        $bin --no-progress -q repair "$base/sampled" --out "$base/without_$step" --config "$base/configs/without_$step.json"
        dirs+=("$base/without_$step")
        echo "without_$step $(diff -rq "$base/all" "$base/without_$step" | wc -l)" >> "$base/changed.txt"
    done
    # settle's own parts, switched off in its config section.
    for part in complete square walls; do
        echo "{\"settle\": {\"$part\": false}}" > "$base/configs/settle_without_$part.json"
        $bin --no-progress -q repair "$base/sampled" --out "$base/settle_without_$part" \
            --config "$base/configs/settle_without_$part.json"
        dirs+=("$base/settle_without_$part")
        echo "settle_without_$part $(diff -rq "$base/all" "$base/settle_without_$part" | wc -l)" >> "$base/changed.txt"
    done
    $bin --no-progress -q eval --pred "${dirs[@]}" --ref "$data/$room/val" --out "$out/$room.json"
    python3 - "$out/$room.json" "$room" "$base/changed.txt" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))
changed = dict(line.split() for line in open(sys.argv[3]))
full = next(r for r in rows if r["name"] == "all")
fail = lambda r: round(r["physics"]["violating_scenes"] * r["scenes"])
print(f"\n{sys.argv[2]} (val, {full['scenes']} rooms)\n")
print("| pipeline | rooms whose layout differs from all steps' | rooms failing check | Δ vs all | contact IoU | Col_mot | CKL |")
print("|---|---:|---:|---:|---:|---:|---:|")
for r in rows:
    name = {"sampled": "no repair", "all": "all steps"}.get(r["name"], r["name"].replace("_without_", " without ").replace("without_", "without "))
    print(f"| {name} | {changed.get(r['name'], '–')} | {fail(r)} | {fail(r) - fail(full):+d} | {r['contact_iou']:.3f} | {r['col_mot']:.4f} | {r['ckl']:.4f} |")
PY
done
