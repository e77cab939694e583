#!/usr/bin/env bash
# The real-motion table (SHADE's PROXD row, on our side): every clip in scenes/motion composed into
# 10 rooms (floor sizes and room types in turn; the clip placed at the first of a fixed list of
# spots and facings that keeps it inside), furnished by the shipped models with guidance and no
# repair (seed 0, one sample), then repaired as `generate` does by default, and evaluated with
# `shade-sim eval` (with physics) per room type, one row per clip; then the rows pooled per clip and
# for all clips (means weighted by scenes) into OUT_DIR/summary.txt.
# Usage: bash scripts/real_motion_eval.sh [OUT_DIR] [REF]
#   REF: a folder of furnished scenes of every room type for eval's reference columns (CKL; not the
#   layout metrics); default scenes/reference.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/real_motion}"
ref="${2:-scenes/reference}"
cargo build --release --quiet
bin=./target/release/shade-sim
rooms=(living bedroom dining)
floors=(5x4 6x5 4.5x4 7x5 5.5x4.5 6x6 4x3.5 8x6 5x5 6.5x4)
spots=("0.5 0.5" "0.3 0.3" "0.7 0.7" "0.3 0.7" "0.7 0.3" "0.2 0.5" "0.8 0.5" "0.5 0.2" "0.5 0.8")
rm -rf "$out"
clips=()
for clip in scenes/motion/*.bvh; do
    name=$(basename "$clip" .bvh)
    clips+=("$name")
    mkdir -p "$out/inputs/$name"
    for k in $(seq 0 9); do
        floor=${floors[$k]}
        room=${rooms[$((k % 3))]}
        w=${floor%x*}
        d=${floor#*x}
        placed=""
        for spot in "${spots[@]}"; do
            for turn in 0 90 180 270; do
                yaw=$(((k * 90 + turn) % 360))
                x=$(echo "$w * ${spot% *}" | bc -l)
                y=$(echo "$d * ${spot#* }" | bc -l)
                if $bin -q import-motion "$clip" --room "$room" --floor "$floor" --place "$x,$y,$yaw" \
                    --out "$out/inputs/$name/${name}_$k.json" 2>/dev/null; then
                    placed="$x,$y,$yaw"
                    break 2
                fi
            done
        done
        if [ -n "$placed" ]; then
            echo "$name $k: $room $floor at $placed" >&2
        else
            echo "$name $k: no spot keeps the clip inside $floor" >&2
        fi
    done
done
# Generated and repaired per room type and clip (eval compares a row with one room type's reference).
for room in "${rooms[@]}"; do
    mkdir -p "$out/ref/$room"
    for f in "$ref"/*.json; do
        grep -q "\"room_type\": *\"$room\"" "$f" && cp "$f" "$out/ref/$room/"
    done
    rows_alone=()
    rows_repaired=()
    for name in "${clips[@]}"; do
        mkdir -p "$out/inputs_by_room/$room/$name"
        for f in "$out/inputs/$name"/*.json; do
            grep -q "\"room_type\": *\"$room\"" "$f" && cp "$f" "$out/inputs_by_room/$room/$name/"
        done
        [ -n "$(ls "$out/inputs_by_room/$room/$name")" ] || continue
        $bin --no-progress -q generate --input "$out/inputs_by_room/$room/$name" --out "$out/alone/$room/$name" \
            --seed 0 --guidance all --no-repair
        $bin --no-progress -q repair "$out/alone/$room/$name" --out "$out/repaired/$room/$name"
        rows_alone+=("$out/alone/$room/$name")
        rows_repaired+=("$out/repaired/$room/$name")
    done
    echo "## $room, model alone (guidance, no repair)"
    $bin --no-progress eval --pred "${rows_alone[@]}" --ref "$out/ref/$room" --no-sca --out "$out/alone_$room.json"
    echo "## $room, repaired"
    $bin --no-progress eval --pred "${rows_repaired[@]}" --ref "$out/ref/$room" --no-sca --out "$out/repaired_$room.json"
done
python3 - "$out" <<'PY' | tee "$out/summary.txt"
import glob, json, sys, collections
out = sys.argv[1]
# Clips with no contact span have no contact IoU (eval reports 0 for them).
def has_contact(clip):
    for f in glob.glob(f"{out}/inputs/{clip}/*.json"):
        for h in json.load(open(f))["humans"]:
            if any(s["action"] in ("sit", "lie", "touch") for s in h["actions"]):
                return True
    return False
keys = ["contact_iou", "col_mot", "r_out", "col_obj"]
print("| clip | scenes | contact IoU | Col_mot | R_out | Col_obj | pass check |  contact IoU | Col_mot | R_out | Col_obj | pass check |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
pooled = {}
for kind in ["alone", "repaired"]:
    acc = collections.defaultdict(lambda: collections.defaultdict(float))
    for room in ["living", "bedroom", "dining"]:
        for row in json.load(open(f"{out}/{kind}_{room}.json")):
            clip = row["name"].rstrip("/").split("/")[-1]
            for target in (clip, "all"):
                a = acc[target]
                n = row["scenes"]
                a["scenes"] += n
                for k in keys:
                    if k == "contact_iou" and not has_contact(clip):
                        continue
                    if row.get(k) is not None:
                        a[k] += row[k] * n
                        a[k + "_n"] += n
                a["pass"] += (1 - row["physics"]["violating_scenes"]) * n
    pooled[kind] = acc
for clip in sorted(pooled["alone"], key=lambda c: (c == "all", c)):
    cells = []
    for kind in ["alone", "repaired"]:
        a = pooled[kind][clip]
        cells += [f"{a[k] / a[k + '_n']:.3f}" if a[k + "_n"] else "-" for k in keys]
        cells.append(f"{100 * a['pass'] / a['scenes']:.0f} %")
    print(f"| {clip} | {int(pooled['alone'][clip]['scenes'])} | " + " | ".join(cells) + " |")
PY
