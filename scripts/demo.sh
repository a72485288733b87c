#!/usr/bin/env bash
# The demo: `simtree demo` makes a small synthetic capture of the default species (4 views, a 7 s
# pull test) in <out>/capture, runs the whole pipeline on it into <out>/result (preprocess,
# register, reconstruct, track, identify, build, simulate, render, report), scores every stage
# against the capture's truth (<out>/result/eval/) and prints the path of the report to open.
# A second run reuses the capture and every stage that has not changed.
# usage: scripts/demo.sh <simtree binary> <output folder>
set -euo pipefail
simtree=$1 out=$2
mkdir -p "$out"
start=$(date +%s)
"$simtree" demo --out "$out"
echo "demo: $(( $(date +%s) - start )) s; open $out/result/report.html in a browser"
