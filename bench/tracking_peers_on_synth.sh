#!/usr/bin/env bash
# Marker tracking side by side on synthetic pull streams (issue 20): ours (`simtree track`) and
# OpenCV's CSRT and KCF (bench/tracking_peers.cc, one tracker per marker), on the same captures,
# from the same init (pull/init.json), scored by the same `simtree eval tracking`. For every
# species and seed `simtree synth` makes a capture (one static view: only the pull stream is
# used; reused when present). Prints one markdown row per capture and tracker, then per tracker
# the medians over the captures and the captures on which ours is better, metric by metric.
# frames/s: CPU time of each tracker's per-frame calls on one thread, frames decoded beforehand,
# all three in the same run of tracking_peers.
#
# usage: bench/tracking_peers_on_synth.sh <simtree> <tracking_peers> <work folder> [seeds] [species...]
#   e.g. bench/tracking_peers_on_synth.sh build/bin/simtree build/bin/tracking_peers /tmp/peers "1 2 3"
#   SYNTH_ARGS="--clean-color", TRACK_ARGS="--motion damped_oscillator" and
#   PEERS_ARGS="--min-box 16" pass options through; PEERS_TAG=_box16 names the peers' folders.
# Leaves <work>/<species>_<seed>.tracks/ (ours) and <work>/<species>_<seed>.peers/{csrt,kcf}/.
set -euo pipefail
simtree=$1
peers=$2
work=$3
seeds=${4:-"1 2 3"}
shift $(( $# >= 4 ? 4 : $# ))
species=${*:-"acer_palmatum magnolia acer_rubrum"}
mkdir -p "$work"

tag=${PEERS_TAG:-}
rows="$work/peers_rows$tag.jsonl"
: > "$rows"
echo "| species | seed | tracker | tracked fraction | success rate | precision | recall | F-score | centre error px (median) | 3D error mm (median / p95) | swaps | frames/s (one core) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for sp in $species; do
  for seed in $seeds; do
    scene="$work/${sp}_$seed"
    [ -f "$scene/gt/markers_2d.json" ] || "$simtree" -q synth --species "$sp" --seed "$seed" \
      --views 1 --no-contact-sheet ${SYNTH_ARGS:-} --out "$scene" > /dev/null
    "$simtree" -q track "$scene/pull" --out "$scene.tracks" ${TRACK_ARGS:-} > /dev/null
    "$peers" --capture "$scene" --out "$scene.peers$tag" ${PEERS_ARGS:-} \
      > "$scene.peers$tag.txt" 2>&1
    for tracker in ours csrt kcf; do
      dir=$([ "$tracker" = ours ] && echo "$scene.tracks" || echo "$scene.peers$tag/$tracker")
      "$simtree" -q eval tracking "$dir" --gt "$scene" --json "$dir.scores.json" > /dev/null
      python3 - "$dir.scores.json" "$scene.peers$tag/speed.json" "$sp" "$seed" "$tracker" "$rows" <<'PY'
import json, sys
path, speed, sp, seed, tracker, rows = sys.argv[1:]
s = json.load(open(path))
fps = json.load(open(speed))["trackers"][tracker]["frames_per_s"]
f = lambda v, d=3: "n/a" if v is None else f"{v:.{d}f}"
print(f"| {sp} | {seed} | {tracker} | {f(s['tracked_fraction'], 4)} | {f(s['success_rate'])} | "
      f"{f(s['precision'])} | {f(s['recall'])} | {f(s['f_score'])} | "
      f"{f(s['median_center_error_px'], 2)} | {f(s['median_error_mm'], 2)} / "
      f"{f(s['p95_error_mm'], 1)} | {s['swap_events']} | {fps:,.0f} |")
keys = ("tracked_fraction", "success_rate", "precision", "recall", "f_score",
        "median_center_error_px", "median_error_mm", "p95_error_mm", "swap_events")
with open(rows, "a") as out:
    out.write(json.dumps({"capture": f"{sp}_{seed}", "tracker": tracker, "frames_per_s": fps,
                          **{k: s[k] for k in keys}}) + "\n")
PY
    done
  done
done

# Per tracker: medians over the captures; "ours better": captures where ours beats that peer.
python3 - "$rows" <<'PY'
import json, sys, statistics
rows = [json.loads(l) for l in open(sys.argv[1])]
cols = [("tracked_fraction", "tracked fraction", 1, 4), ("success_rate", "success rate", 1, 3),
        ("precision", "precision", 1, 3), ("recall", "recall", 1, 3), ("f_score", "F-score", 1, 3),
        ("median_center_error_px", "centre error px", -1, 2), ("median_error_mm", "3D error mm", -1, 2),
        ("p95_error_mm", "3D p95 mm", -1, 1), ("swap_events", "swaps", -1, 0),
        ("frames_per_s", "frames/s", 1, 0)]
by = {}
for r in rows: by.setdefault(r["tracker"], {})[r["capture"]] = r
def med(t, k):
    v = [r[k] for r in by[t].values() if r[k] is not None]
    return statistics.median(v) if v else None
print()
print("| tracker | captures | " + " | ".join(c[1] + " (median)" for c in cols) + " |")
print("| --- | --- |" + " --- |" * len(cols))
for t in by:
    cells = []
    for k, _, _, d in cols:
        m = med(t, k)
        cells.append("n/a" if m is None else f"{m:,.{d}f}")
    print(f"| {t} | {len(by[t])} | " + " | ".join(cells) + " |")
print()
print("| ours against | " + " | ".join(c[1] for c in cols) + " |")
print("| --- |" + " --- |" * len(cols))
for peer in (t for t in by if t != "ours"):
    cells = []
    for k, _, sign, _ in cols:
        n = total = 0
        for cap, r in by["ours"].items():
            p = by[peer].get(cap)
            if p is None or r[k] is None or p[k] is None: continue
            total += 1
            n += sign * (r[k] - p[k]) > 0 or (k == "swap_events" and r[k] == p[k] == 0)
        cells.append(f"{n} of {total}")
    print(f"| {peer}: ours better (swaps: or both 0) | " + " | ".join(cells) + " |")
PY
