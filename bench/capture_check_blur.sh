#!/usr/bin/env bash
# Where capture-check's blur limit comes from: a synthetic capture's pull stream blurred as an
# out-of-focus lens (Gaussian, sigma px) and as a sideways camera motion (a line, px), each copy
# checked by `simtree capture-check` (the blur effect of its first pull frame on the tree) and
# tracked by `simtree track`, scored against synth's truth. Prints
# one markdown row per capture and blur.
#
# usage: bench/capture_check_blur.sh <build folder> <work folder> [seeds] [species...]
#   e.g. bench/capture_check_blur.sh build /tmp/blur "1" acer_palmatum magnolia acer_rubrum
#   BLURS="sigma:0 sigma:1 motion:6" picks the blurs.
set -euo pipefail
build=$1
work=$2
seeds=${3:-"1"}
shift $(( $# >= 3 ? 3 : $# ))
species=${*:-"acer_palmatum magnolia acer_rubrum"}
blurs=${BLURS:-"sigma:0 sigma:0.5 sigma:1 sigma:1.5 sigma:2 sigma:3 motion:3 motion:6 motion:10 motion:16"}
simtree=$build/bin/simtree
mkdir -p "$work"

echo "| species | seed | blur | blur effect | tracked fraction | 3D error mm (median) | swaps |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
for sp in $species; do
  for seed in $seeds; do
    scene="$work/${sp}_$seed"
    [ -f "$scene/pull/init.json" ] || "$simtree" -q synth --quick --species "$sp" --seed "$seed" \
      --duration 5 --no-contact-sheet --out "$scene" > /dev/null
    for blur in $blurs; do
      kind=${blur%%:*}
      size=${blur#*:}
      copy="$work/${sp}_${seed}_${kind}_$size"
      rm -rf "$copy"
      mkdir -p "$copy/pull"
      cp "$scene/capture.json" "$copy/"
      ln -s "$scene/scans" "$copy/scans"
      ln -s "$scene/gt" "$copy/gt"
      ln -s "$scene/pull/depth" "$copy/pull/depth"
      cp "$scene/pull/"*.json "$scene/pull/frames.csv" "$copy/pull/"
      "$build/bin/blur_frames" "$scene/pull/color" "$copy/pull/color" "--$kind" "$size" > /dev/null
      "$simtree" -q capture-check "$copy" --no-register --json > "$copy.check.json" || true
      "$simtree" -q track "$copy/pull" --init "$copy/pull/init.json" --out "$copy.tracks" > /dev/null
      "$simtree" -q eval tracking "$copy.tracks" --gt "$copy" --json "$copy.scores.json" > /dev/null
      python3 - "$copy.check.json" "$copy.scores.json" "$sp" "$seed" "$kind $size px" <<'PY'
import json, sys
check = json.load(open(sys.argv[1]))
scores = json.load(open(sys.argv[2]))
def pull_value(name):
    for c in check["checks"]:
        if c["name"] == name and c["subject"].startswith("pull frame"):
            return c["value"]
    return float("nan")
print(f"| {sys.argv[3]} | {sys.argv[4]} | {sys.argv[5]} | {pull_value('blur'):.3f} | "
      f"{scores['tracked_fraction']:.4f} | "
      f"{scores['median_error_mm']:.2f} | {scores['swap_events']} |")
PY
    done
  done
done
