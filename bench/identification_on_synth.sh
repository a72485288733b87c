#!/usr/bin/env bash
# Identification on synthetic pull tests, scored against the FEM truth (issue 8's bench):
# for every species and seed, `simtree synth` makes a capture, its true marker tracks get a
# tracker's errors (2.5 mm RMS, gaps, jumps, lost where the tape is not seen), `simtree identify`
# estimates every link with all three estimators over 10 s of free decay, `simtree build` makes the
# simulation-ready tree on the true static tree, and `simtree eval identification` scores links and
# branches. Prints one markdown row per capture and estimator, then the medians.
#
# usage: bench/identification_on_synth.sh <simtree binary> <work folder> [seeds] [species...]
#   e.g. bench/identification_on_synth.sh build/bin/simtree /tmp/ident "1 2 3"
set -euo pipefail
simtree=$1
work=$2
seeds=${3:-"1 2 3"}
shift $(( $# >= 3 ? 3 : $# ))
species=${*:-"acer_palmatum magnolia acer_rubrum"}
mkdir -p "$work"

echo "| species | seed | estimator | links scored | not estimated | median df/f | median dzeta/zeta | measured f range | measured zeta range | branches: interpolated median df/f |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for sp in $species; do
  for seed in $seeds; do
    scene="$work/${sp}_$seed"
    [ -f "$scene/gt/modal.json" ] || "$simtree" -q synth --species "$sp" --seed "$seed" \
      --no-contact-sheet --out "$scene" > /dev/null
    "$simtree" -q identify "$scene/gt/trajectories.csv" --links "$scene/pull/markers.json" \
      --tree "$scene/gt/tree.json" --camera-pose "$scene/gt/pull_camera.json" \
      --out "$work/${sp}_$seed.materials.json" --no-plots --window 10 \
      --simulate-tracker-noise 2.5 --visibility "$scene/gt/markers_2d.json" --seed "$seed" \
      > "$work/${sp}_$seed.identify.txt" 2>&1
    "$simtree" -q build "$scene/gt/tree.json" -m "$work/${sp}_$seed.materials.json" \
      -o "$work/${sp}_$seed.simready.json" > /dev/null 2>&1
    "$simtree" -q eval identification "$work/${sp}_$seed.materials.json" --gt "$scene" \
      --tree "$work/${sp}_$seed.simready.json" --json "$work/${sp}_$seed.scores.json" > /dev/null
    python3 - "$work/${sp}_$seed.scores.json" "$work/${sp}_$seed.materials.json" "$sp" "$seed" <<'EOF'
import json, sys
scores = json.load(open(sys.argv[1]))
materials = json.load(open(sys.argv[2]))
sp, seed = sys.argv[3], sys.argv[4]
def pct(v): return "-" if v is None else f"{100 * v:.2f}%"
interp = scores.get("branches", {}).get("interpolated", {})
for name, s in scores["links"].items():
    f, z = [], []
    for link in materials["links"]:
        e = link.get("estimators", {}).get(name, {})
        if e.get("status") == "ok":
            f.append(e["frequency_hz"]); z.append(e["damping_ratio"])
    fr = f"{min(f):.2f}-{max(f):.2f} Hz" if f else "-"
    zr = f"{min(z):.3f}-{max(z):.3f}" if z else "-"
    print(f"| {sp} | {seed} | {name} | {s['scored']} | {s['not_estimated']} | "
          f"{pct(s['median_frequency_error'])} | {pct(s['median_damping_error'])} | {fr} | {zr} | "
          f"{pct(interp.get('median_frequency_error')) if name == materials['estimator'] else ''} |")
EOF
  done
done
