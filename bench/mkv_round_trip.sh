#!/usr/bin/env bash
# A capture's pull test through Azure Kinect recordings and back (issue 24: the same materials
# within 1%): for every species and seed, `synth` a small capture with a 1280x720 colour camera,
# `run` it as written (PNG folder), then export its pull stream to pull.mkv (MJPEG colour, 16-bit
# depth, calibration attachment), read it back with `capture-from`, put the read-back stream in
# place of the PNG one (markers.json and init.json kept) and `run` again. Prints one markdown row
# per capture: every identified link's frequency and damping ratio from both, the largest
# relative differences, the same for every branch of the simulation-ready trees `build` made
# (build/simready.json: the values the product carries, after build's uncertain-value flagging),
# and the tracked share of marker samples.
#
# usage: bench/mkv_round_trip.sh <simtree binary> <work folder> [seeds] [species...]
#   e.g. bench/mkv_round_trip.sh build/bin/simtree /tmp/mkv "1 2"
set -euo pipefail
simtree=$1
work=$2
seeds=${3:-"1"}
shift $(( $# >= 3 ? 3 : $# ))
species=${*:-"acer_palmatum magnolia acer_rubrum"}
mkdir -p "$work"

echo "| species | seed | links (png / mkv) | links: max / median df/f | links: max / median dzeta/zeta | branches (measured png / mkv) | branches: max / median df/f | branches: max / median dzeta/zeta | tracked (png / mkv) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for sp in $species; do
  for seed in $seeds; do
    dir="$work/${sp}_$seed"
    rm -rf "$dir" && mkdir -p "$dir"
    log="$dir/log.txt"
    if ! {
      "$simtree" -q synth --quick --species "$sp" --seed "$seed" --duration 7 \
        --color-size 1280x720 --no-contact-sheet --out "$dir/png" &&
      "$simtree" -q capture-export "$dir/png" --out "$dir/rec" --pull-only &&
      "$simtree" -q capture-from --pull "$dir/rec/pull.mkv" --snap-times --out "$dir/back" &&
      cp -r "$dir/png" "$dir/mkv" && rm -rf "$dir/mkv/pull" && cp -r "$dir/back/pull" "$dir/mkv/pull" &&
      cp "$dir/png/pull/markers.json" "$dir/png/pull/init.json" "$dir/mkv/pull/" &&
      "$simtree" -q run "$dir/png" --out "$dir/png_result" --no-render &&
      "$simtree" -q run "$dir/mkv" --out "$dir/mkv_result" --no-render
    } > "$log" 2>&1; then
      echo "| $sp | $seed | failed: $(grep -m1 -i 'error' "$log" | cut -c1-120) | | | | | | | |"
      continue
    fi
    python3 - "$dir" "$sp" "$seed" <<'PY'
import csv, glob, json, os, statistics, sys
d, sp, seed = sys.argv[1:4]

def links(result):
    m = json.load(open(glob.glob(os.path.join(result, "identify", "materials.json"))[0]))
    out = {}
    for link in m.get("links", []):
        if link.get("status") == "ok" and link.get("damping_ratio") is not None:
            out[link["label"]] = (link["frequency_hz"], link["damping_ratio"])
    return out

def tracked(result):
    with open(os.path.join(result, "track", "trajectories.csv")) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return sum(int(r["valid"]) for r in rows) / max(1, len(rows))

def branches(result):
    tree = json.load(open(os.path.join(result, "build", "simready.json")))
    out = []
    for branch in tree["branches"]:
        material = branch["material"]
        mode = material["modes"][0]
        out.append((mode["frequency_hz"], mode["damping_ratio"], material.get("source")))
    return out

def rel(x, y):
    return [abs(v - u) / u for u, v in zip(x, y)]

pct = lambda v: f"{100 * v:.2f}%" if v is not None else "–"
mx = lambda v: max(v) if v else None
md = lambda v: statistics.median(v) if v else None
both = lambda v: f"{pct(mx(v))} / {pct(md(v))}"

a, b = links(os.path.join(d, "png_result")), links(os.path.join(d, "mkv_result"))
common = sorted(set(a) & set(b))
df = rel([a[k][0] for k in common], [b[k][0] for k in common])
dz = rel([a[k][1] for k in common], [b[k][1] for k in common])
ta, tb = branches(os.path.join(d, "png_result")), branches(os.path.join(d, "mkv_result"))
if len(ta) != len(tb):
    sys.exit(f"the two runs built trees of {len(ta)} and {len(tb)} branches")
bf = rel([t[0] for t in ta], [t[0] for t in tb])
bz = rel([t[1] for t in ta], [t[1] for t in tb])
measured = lambda t: sum(1 for x in t if x[2] == "measured")
print(f"| {sp} | {seed} | {len(a)} / {len(b)} | {both(df)} | {both(dz)} | "
      f"{len(ta)} ({measured(ta)} / {measured(tb)}) | {both(bf)} | {both(bz)} | "
      f"{pct(tracked(os.path.join(d, 'png_result')))} / "
      f"{pct(tracked(os.path.join(d, 'mkv_result')))} |")
PY
  done
done
