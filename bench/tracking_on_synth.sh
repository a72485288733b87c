#!/usr/bin/env bash
# Marker tracking on synthetic pull streams, scored against synth's truth (issue 20's bench): for
# every species and seed, `simtree synth` makes a capture (one static view: only the pull stream
# is used), the tracker starts from pull/init.json (or, on captures without one, from the true
# boxes' centres of frame 0, bench/track_init_from_truth.py), `simtree track` follows the markers
# and `simtree eval tracking` scores them. Prints one markdown row per capture.
#
# usage: bench/tracking_on_synth.sh <simtree binary> <work folder> [seeds] [species...]
#   e.g. bench/tracking_on_synth.sh build/bin/simtree /tmp/trk "1 2 3"
#   SYNTH_ARGS="--duration 8" and TRACK_ARGS="--motion damped_oscillator" pass options through.
set -euo pipefail
simtree=$1
work=$2
seeds=${3:-"1 2 3"}
shift $(( $# >= 3 ? 3 : $# ))
species=${*:-"acer_palmatum magnolia acer_rubrum"}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"

echo "| species | seed | frames | markers | tracked fraction | success rate | precision | recall | F-score | centre error px (median) | 3D error mm (median / p95) | swaps | track s |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for sp in $species; do
  for seed in $seeds; do
    scene="$work/${sp}_$seed"
    [ -f "$scene/gt/markers_2d.json" ] || "$simtree" -q synth --species "$sp" --seed "$seed" \
      --views 1 --no-contact-sheet ${SYNTH_ARGS:-} --out "$scene" > /dev/null
    init="$scene/pull/init.json"
    if [ ! -f "$init" ]; then
      init="$work/${sp}_$seed.init.json"
      python3 "$here/track_init_from_truth.py" "$scene" "$init"
    fi
    start=$(date +%s.%N)
    "$simtree" -q track "$scene/pull" --init "$init" --out "$work/${sp}_$seed.tracks" \
      ${TRACK_ARGS:-} > /dev/null
    end=$(date +%s.%N)
    "$simtree" -q eval tracking "$work/${sp}_$seed.tracks" --gt "$scene" \
      --json "$work/${sp}_$seed.scores.json" > /dev/null
    python3 - "$work/${sp}_$seed.scores.json" "$sp" "$seed" "$(echo "$end - $start" | bc)" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
f = lambda v, d=3: "n/a" if v is None else f"{v:.{d}f}"
print(f"| {sys.argv[2]} | {sys.argv[3]} | {s['frames']} | {len(s['markers'])} | "
      f"{f(s['tracked_fraction'], 4)} | {f(s['success_rate'])} | {f(s['precision'])} | "
      f"{f(s['recall'])} | {f(s['f_score'])} | {f(s['median_center_error_px'], 2)} | "
      f"{f(s['median_error_mm'], 2)} / {f(s['p95_error_mm'], 1)} | {s['swap_events']} | "
      f"{float(sys.argv[4]):.1f} |")
PY
  done
done
