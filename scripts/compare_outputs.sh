#!/usr/bin/env bash
# Runs every stage with two simtree binaries on the same inputs and compares what they wrote,
# file by file: the proof that a refactor changed no output. JSON files are compared after
# dropping wall-clock fields (seconds, times in ms), Markdown tables after dropping their time
# columns; everything else byte for byte. Both run on one thread: with several, Open3D's OpenMP
# reductions sum in varying order and registration's poses differ in the last bits run to run.
#
#   scripts/compare_outputs.sh OLD_SIMTREE NEW_SIMTREE WORK_DIR [SHARED_DATA_DIR] [STAGES...]
#
# STAGES (default: all): synth preprocess register reconstruct identify build simulate render
# convert. Exit status 0 when every output matches, 1 otherwise (the differing files are listed).
set -euo pipefail

old=$(realpath "$1")
new=$(realpath "$2")
work=$3
data=${4:-$(dirname "$0")/../../shared/data}
data=$(realpath "$data")
shift 4 2>/dev/null || shift $#
stages=("$@")
[ ${#stages[@]} -eq 0 ] && stages=(synth preprocess register reconstruct identify build simulate render convert)
mkdir -p "$work"
work=$(realpath "$work")

want() { local s; for s in "${stages[@]}"; do [ "$s" = "$1" ] && return 0; done; return 1; }

# run NAME SIDE ARGS...: one command with one binary, its output in $work/SIDE/NAME.log.
run() {
  local name=$1 side=$2 bin
  shift 2
  bin=$old
  [ "$side" = new ] && bin=$new
  echo "[$side] simtree $*" >&2
  # A failing command is an output too: its exit status is compared like a file.
  local code=0
  (cd "$work/$side" && OMP_NUM_THREADS=1 "$bin" -q --threads 1 "$@") >"$work/$side/$name.log" 2>&1 || code=$?
  echo "$code" >"$work/$side/$name.exit"
  [ "$code" -eq 0 ] || echo "[$side] $name exited with $code: see $work/$side/$name.log" >&2
}

# The old side is kept between runs of the same old binary and stages (it is the slow half).
stamp="$(sha256sum "$old" | cut -c1-16) ${stages[*]}"
for side in old new; do
  if [ "$side" = old ] && [ -f "$work/old/.stamp" ] && [ "$(cat "$work/old/.stamp")" = "$stamp" ]; then
    echo "[old] outputs of this binary kept from an earlier run" >&2
    continue
  fi
  rm -rf "${work:?}/$side"
  mkdir -p "$work/$side"
  if want synth; then
    run synth_quick $side synth --quick --seed 3 --out quick
    run synth_rubrum $side synth --species acer_rubrum --seed 2 --out rubrum
  fi
  if want preprocess; then run preprocess $side preprocess quick --out quick_clean; fi
  if want register; then
    run register_quick $side register quick --out quick_reg
    run register_rubrum $side register rubrum --out rubrum_reg
  fi
  if want reconstruct; then
    run reconstruct_synth $side reconstruct rubrum_reg/merged.ply --out rubrum_static.json
    for scan in tree1 tree7 rtwig_cloud itsme_tree2; do
      run "reconstruct_$scan" $side reconstruct "$data/real-scans/$scan.xyz" --out "$scan.json"
    done
  fi
  if want identify; then
    run identify $side identify rubrum/gt/trajectories.csv --links rubrum/pull/markers.json \
      --out rubrum_materials.json
    run eval_identification $side eval identification rubrum_materials.json --gt rubrum/ \
      --json rubrum_eval.json
  fi
  if want build; then
    run build $side build rubrum/gt/tree.json --materials rubrum_materials.json \
      --out rubrum_simready.json
  fi
  if want simulate; then
    run simulate $side simulate rubrum_simready.json --pull 1 --force 80 --hold 1 --release 2 \
      --duration 4 --out rubrum_sim
  fi
  if want render; then
    run render $side render rubrum_simready.json --pull 1 --force 80 --release 1 --duration 1 \
      --out rubrum_frames
  fi
  if want convert; then
    run convert $side convert "$data/authors-demo/tree_model/tree01.txt" tree01.json \
      --params "$data/authors-demo/tree_parameters.txt"
    run mesh $side mesh tree01.json --out tree01.ply
  fi
  [ "$side" = old ] && echo "$stamp" >"$work/old/.stamp"
done

# Drops wall-clock fields from a JSON document (recursively) and prints it canonically.
normalize_json() {
  python3 - "$1" <<'EOF'
import json, re, sys
timing = re.compile(r"(seconds|_ms$|^ms$|wall|elapsed|_s_total|timing)")
def clean(v):
    if isinstance(v, dict):
        return {k: clean(x) for k, x in v.items() if not timing.search(k)}
    if isinstance(v, list):
        return [clean(x) for x in v]
    return v
print(json.dumps(clean(json.load(open(sys.argv[1]))), sort_keys=True, indent=1))
EOF
}

# Drops the columns of Markdown tables whose header names a time.
normalize_md() {
  python3 - "$1" <<'EOF'
import re, sys
drop = []
for line in open(sys.argv[1]):
    if line.startswith("|"):
        cells = line.rstrip("\n").strip("|").split("|")
        if not drop and not set(line) <= set("|-: \n"):
            drop = [i for i, c in enumerate(cells) if re.search(r"time|\(ms\)|\(s\)", c)]
        line = "|" + "|".join(c for i, c in enumerate(cells) if i not in drop) + "|\n"
    else:
        drop = []
    sys.stdout.write(line)
EOF
}

status=0
same=0
while IFS= read -r rel; do
  a="$work/old/$rel"
  b="$work/new/$rel"
  case "$rel" in *.log) continue ;; esac
  if [ ! -f "$b" ]; then
    echo "missing in new: $rel"; status=1; continue
  fi
  if cmp -s "$a" "$b"; then same=$((same + 1)); continue; fi
  if [[ "$rel" == *.json ]] && diff -q <(normalize_json "$a") <(normalize_json "$b") >/dev/null 2>&1; then
    same=$((same + 1)); continue
  fi
  if [[ "$rel" == *.md ]] && diff -q <(normalize_md "$a") <(normalize_md "$b") >/dev/null 2>&1; then
    same=$((same + 1)); continue
  fi
  echo "differs: $rel"; status=1
done < <(cd "$work/old" && find . -type f ! -name .stamp | sed 's|^\./||' | sort)
while IFS= read -r rel; do
  [ -f "$work/old/$rel" ] || { echo "only in new: $rel"; status=1; }
done < <(cd "$work/new" && find . -type f ! -name '*.log' | sed 's|^\./||' | sort)
echo "compare_outputs: $same files identical$([ $status -eq 0 ] && echo ', no difference' || echo ', differences above')"
exit $status
