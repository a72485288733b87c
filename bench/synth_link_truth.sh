#!/usr/bin/env bash
# The FEM truth of the marker links against the paper's Table IV, per species over many seeds,
# without rendering anything (`simtree synth --truth-only`, ~4 s a capture): the first mode's
# range, the links' frequency and damping ranges, how many links' frequencies lie inside Table IV,
# and the largest ratio of a link's frequency to its tree's first mode. A species may be a preset
# or a species JSON file (e.g. {"base": "magnolia", "wood": {...}}) to measure a change first.
#
# usage: bench/synth_link_truth.sh <simtree binary> <work folder> "<seeds>" species...
#   e.g. bench/synth_link_truth.sh build/bin/simtree /tmp/truth "$(seq -s' ' 1 10)" \
#          acer_palmatum magnolia acer_rubrum
# SYNTH_ARGS adds options to every `simtree synth` (use a work folder per value: captures are
# reused), e.g. SYNTH_ARGS="--pull-position 0.65" for the rope where it was tied before.
set -euo pipefail
simtree=$1; work=$2; seeds=$3; shift 3
for sp in "$@"; do
  if [ -f "$sp" ]; then arg=(--species-file "$sp"); name=$(basename "$sp" .json); else arg=(--species "$sp"); name=$sp; fi
  for s in $seeds; do
    [ -f "$work/${name}_$s/gt/modal.json" ] || "$simtree" -q synth "${arg[@]}" --seed "$s" \
      --truth-only ${SYNTH_ARGS:-} --out "$work/${name}_$s" > /dev/null
  done
  python3 - "$work" "$name" "$seeds" <<'PY'
import json, sys
work, name, seeds = sys.argv[1], sys.argv[2], sys.argv[3].split()
table = {"acer_palmatum": (1.07, 1.50), "magnolia": (0.72, 1.19), "acer_rubrum": (0.93, 1.50)}
lo, hi = next((v for k, v in table.items() if name.startswith(k)), (0.0, float("inf")))
f_all, z_all, f1, ratio, inside, per_seed = [], [], [], [], 0, []
for s in seeds:
    d = json.load(open(f"{work}/{name}_{s}/gt/modal.json"))
    f = [l["frequency_hz"] for l in d["links"]]
    first = d["modes"][0]["frequency_hz"]
    f_all += f; z_all += [l["damping_ratio"] for l in d["links"]]; f1.append(first)
    ratio.append(max(f) / first); inside += sum(lo <= v <= hi for v in f)
    per_seed.append(f"{s}: {first:.2f}/{max(f):.2f}")
print(f"{name}: first mode {min(f1):.2f}-{max(f1):.2f} Hz, links {min(f_all):.2f}-{max(f_all):.2f} Hz, "
      f"zeta {min(z_all):.3f}-{max(z_all):.3f}, frequency inside Table IV {inside} of {len(f_all)}, "
      f"highest link / first mode {max(ratio):.2f}")
print("  per seed, first mode / highest link (Hz):", ", ".join(per_seed))
PY
done
