#!/usr/bin/env bash
# A model on a validation split over several sampling seeds, as settings are chosen in
# docs/RESULTS.md: scripts/val_eval.sh once per seed (into OUT/seedN), then one table with each
# seed's rooms failing `check` and SCA, alone and repaired, and their mean. On the ~300-room living
# and dining val splits two seeds of one model differ by up to 0.06 in SCA (docs/RESULTS.md, "Two
# seeds of the shipped living model"), far more than the judge's own repeats, so one seed decides
# nothing there.
# Usage: bash scripts/val_seeds.sh MODEL_DIR DATA_DIR OUT_DIR [SEEDS] [GENERATE_ARGS…]
#   SEEDS is a comma-separated list (default 0,1); GENERATE_ARGS go to val_eval.sh as they are.
#   e.g. bash scripts/val_seeds.sh models/living data/living out/val/living 0,1,2
set -euo pipefail
cd "$(dirname "$0")/.."
model="$1"
data="$2"
out="$3"
seeds="${4:-0,1}"
IFS=',' read -ra list <<<"$seeds"
mkdir -p "$out"
for seed in "${list[@]}"; do
    echo "== seed $seed" >&2
    bash scripts/val_eval.sh "$model" "$data" "$out/seed$seed" "$seed" "${@:5}" >"$out/seed$seed.log"
done
python3 - "$out" "${list[@]}" <<'EOF'
import json, sys
out, seeds = sys.argv[1], sys.argv[2:]
rows = []
for seed in seeds:
    alone, repaired = json.load(open(f"{out}/seed{seed}/eval.json"))
    failing = [round(r["physics"]["violating_scenes"] * r["scenes"]) for r in (alone, repaired)]
    sca = [r["sca"]["accuracy"] if r.get("sca") else float("nan") for r in (alone, repaired)]
    rows.append((seed, failing, sca, alone["scenes"]))
print("seed  rooms  failing alone / repaired  SCA alone / repaired")
for seed, failing, sca, scenes in rows:
    print(f"{seed:<5} {scenes:<6} {failing[0]:>13} / {failing[1]:<10} {sca[0]:.3f} / {sca[1]:.3f}")
mean = lambda xs: sum(xs) / len(xs)
print(
    f"{'mean':<5} {'':<6} {mean([r[1][0] for r in rows]):>13.1f} / {mean([r[1][1] for r in rows]):<10.1f} "
    f"{mean([r[2][0] for r in rows]):.3f} / {mean([r[2][1] for r in rows]):.3f}"
)
EOF
