#!/usr/bin/env bash
# What each repair step is worth: the val split's inputs sampled once with the shipped models
# (`all` guidance, no repair, seed 0), then repaired by the full pipeline and by the pipeline with
# each step switched off in turn (a config without it, `shade-sim repair --config`), and by settle
# without each of its parts (completion, squaring, walls), every folder a
# row of `shade-sim eval` against the val split; prints a Markdown table (rooms failing `check`,
# contact IoU, Col_mot, CKL, the rooms each step's absence costs, and how many rooms' layouts it
# changes at all) and writes OUT_DIR/<room>.json.
# Usage: [SEEDS=0,1,2] bash scripts/repair_ablation.sh [DATA_DIR] [OUT_DIR] [LIMIT] [ROOMS…]
#   LIMIT: only the first LIMIT val inputs of each room (0 = all, the default).
#   SEEDS: the sampling seeds, comma-separated as val_seeds.sh takes them (spaces also do; default
#   0); with several, every folder is drawn and repaired once per seed and the table sums the
#   rooms over the seeds (one seed's spread is about as large as what the smaller steps earn) and
#   averages the metrics. OUT_DIR/<room>.seed<S>.json per seed.
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
seed_list="${SEEDS:-0}"
seeds=(${seed_list//,/ })
for room in "${rooms[@]}"; do
    reports=()
    for seed in "${seeds[@]}"; do
        base="$out/$room/seed$seed"
        rm -rf "$base" && mkdir -p "$base/inputs" "$base/configs"
        files=$(ls "$data/$room/val"/*.json | sort)
        [ "$limit" -gt 0 ] && files=$(echo "$files" | sed -n "1,${limit}p")
        for f in $files; do cp "$f" "$base/inputs/"; done
        $bin --no-progress -q generate --input "$base/inputs" --out "$base/sampled" --seed "$seed" --guidance all --no-repair
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
        $bin --no-progress -q eval --pred "${dirs[@]}" --ref "$data/$room/val" --out "$out/$room.seed$seed.json"
        reports+=("$out/$room.seed$seed.json" "$base/changed.txt")
    done
    python3 - "$room" "${reports[@]}" <<'PY'
import json, sys
room, pairs = sys.argv[1], sys.argv[2:]
runs = [(json.load(open(pairs[i])), dict(line.split() for line in open(pairs[i + 1]))) for i in range(0, len(pairs), 2)]
fail = lambda r: round(r["physics"]["violating_scenes"] * r["scenes"])
names = [r["name"] for r in runs[0][0]]
row = lambda rows, name: next(r for r in rows if r["name"] == name)
total = lambda name, f: sum(f(row(rows, name)) for rows, _ in runs)
mean = lambda name, key: total(name, lambda r: r[key]) / len(runs)
full = total("all", fail)
print(f"\n{room} (val, {runs[0][0][0]['scenes']} rooms, {len(runs)} seed(s); rooms summed over the seeds, metrics averaged)\n")
print("| pipeline | rooms whose layout differs from all steps' | rooms failing check | Δ vs all | contact IoU | Col_mot | CKL |")
print("|---|---:|---:|---:|---:|---:|---:|")
for name in names:
    label = {"sampled": "no repair", "all": "all steps"}.get(name, name.replace("_without_", " without ").replace("without_", "without "))
    changed = sum(int(c[name]) for _, c in runs) if name in runs[0][1] else "–"
    print(f"| {label} | {changed} | {total(name, fail)} | {total(name, fail) - full:+d} | {mean(name, 'contact_iou'):.3f} "
          f"| {mean(name, 'col_mot'):.4f} | {mean(name, 'ckl'):.4f} |")
PY
done
