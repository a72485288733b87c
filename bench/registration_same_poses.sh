#!/usr/bin/env bash
# Two simtree binaries register the same synthetic captures: does a change to registration keep
# every view's pose? For each species and seed, `synth` (10 views, a short pull stream: only the
# scans are registered), then `register` with each binary; prints one markdown row per capture:
# views registered by each, the largest difference between the two poses.json files' matrices,
# and each binary's wall time.
#
# usage: bench/registration_same_poses.sh <before binary> <after binary> <work folder> [seeds] [species...]
#   e.g. bench/registration_same_poses.sh /tmp/simtree_before build/bin/simtree /tmp/poses "1 2"
set -euo pipefail
before=$1
after=$2
work=$3
seeds=${4:-"1 2"}
shift $(( $# >= 4 ? 4 : $# ))
species=${*:-"acer_palmatum magnolia acer_rubrum"}
mkdir -p "$work"

echo "| capture | views registered (before, after) | largest pose difference | wall (s): before, after |"
echo "| --- | --- | --- | --- |"
for sp in $species; do
  for seed in $seeds; do
    capture="$work/${sp}_$seed"
    if [ ! -f "$capture/gt/scan_poses.json" ]; then
      "$after" -q synth --species "$sp" --seed "$seed" --duration 4.5 --fps 2 --out "$capture" \
        > "$capture.synth.log" 2>&1
    fi
    walls=()
    for which in before after; do
      start=$(date +%s.%N)
      "${!which}" -q register "$capture" --out "$work/${sp}_${seed}_$which" \
        > "$work/${sp}_${seed}_$which.log" 2>&1
      walls+=("$(echo "$(date +%s.%N) - $start" | bc)")
    done
    python3 - "$work/${sp}_${seed}_before/poses.json" "$work/${sp}_${seed}_after/poses.json" \
      "$sp seed $seed" "${walls[0]}" "${walls[1]}" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
label, wall_a, wall_b = sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
diff = 0.0
for va, vb in zip(a["views"], b["views"]):
    if va["registered"] != vb["registered"]:
        diff = float("inf")
    elif va["registered"]:
        diff = max(diff, max(abs(x - y) for x, y in zip(va["frame_from_camera"], vb["frame_from_camera"])))
print(f"| {label} | {a['registered']}, {b['registered']} of {a['views_total']} | {diff:.2g} | {wall_a:.0f}, {wall_b:.0f} |")
PY
  done
done
