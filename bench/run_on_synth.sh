#!/usr/bin/env bash
# The whole chain on synthetic captures (issue 21's bar: simulated held-out markers within a
# normalised RMSE of 0.3 of the truth over the first 5 s after the release): for every species and
# seed, `simtree demo` synthesises a small capture (4 views, 7 s pull), runs the pipeline (without
# the side-by-side render) and scores it with `simtree eval`. Prints one markdown row per capture
# and the median over all held-out markers.
#
# usage: bench/run_on_synth.sh <simtree binary> <work folder> [seeds] [species...]
#   e.g. bench/run_on_synth.sh build/bin/simtree /tmp/chain "1 2"
set -euo pipefail
simtree=$1
work=$2
seeds=${3:-"1 2"}
shift $(( $# >= 3 ? 3 : $# ))
species=${*:-"acer_palmatum magnolia acer_rubrum"}
mkdir -p "$work"

echo "| species | seed | wall (s) | pull camera rot (deg) / tree RMS (mm) | recall / precision | links scored, median df/f | held-out markers: NRMSE | f sim / true (Hz) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for sp in $species; do
  for seed in $seeds; do
    out="$work/${sp}_$seed"
    start=$(date +%s.%N)
    if ! "$simtree" -q demo --out "$out" --species "$sp" --seed "$seed" --no-render \
        > "$out.log" 2>&1; then
      echo "| $sp | $seed | failed: $(grep -m1 'error' "$out.log" | cut -c1-120) | | | | | |"
      continue
    fi
    wall=$(echo "$(date +%s.%N) - $start" | bc)
    python3 - "$out/result/eval/eval.json" "$sp" "$seed" "$wall" <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))
sp, seed, wall = sys.argv[2], sys.argv[3], float(sys.argv[4])
def f(v, fmt="{:.2f}"):
    return "–" if v is None else fmt.format(v)
reg = e["registration"]
pc = reg.get("pull_camera") or {}
rec = e["reconstruction"]
idn = e["identification"]
ch = e["chain"]
nr = ", ".join(f(m["nrmse"]) for m in ch.get("markers", []))
fr = ", ".join(f"{f(m['simulated_frequency_hz'])}/{f(m['true_frequency_hz'])}" for m in ch.get("markers", []))
print(f"| {sp} | {seed} | {wall:.0f} | {f(pc.get('rotation_deg'))} / {f(pc.get('tree_rms_m', 0) * 1e3, '{:.0f}')} | "
      f"{f(rec.get('recall'))} / {f(rec.get('precision'))} | {idn.get('links', '–')}, {f(idn.get('median_frequency_error'), '{:.3f}')} | {nr} | {fr} |")
PY
  done
done
python3 - "$work" <<'PY'
import glob, json, statistics, sys
values = []
for path in glob.glob(sys.argv[1] + "/*/result/eval/eval.json"):
    for m in json.load(open(path))["chain"].get("markers", []):
        if m["nrmse"] is not None:
            values.append(m["nrmse"])
if values:
    print(f"\nheld-out markers: {len(values)}, median NRMSE {statistics.median(values):.2f}, "
          f"within 0.3: {sum(v <= 0.3 for v in values)}")
PY
