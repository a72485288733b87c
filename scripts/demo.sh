#!/usr/bin/env bash
# The demo: the paper's authors' tree01 with its material parameters becomes a simtree JSON tree
# and a generalized-cylinder mesh, simtree prints what it holds, then pulls a first-level branch
# with a rope, releases it and writes the animation (glTF for Blender / three.js) and marker tracks.
# usage: scripts/demo.sh <simtree binary> <shared data folder> <output folder>
set -euo pipefail
simtree=$1 data=$2 out=$3
demo="$data/authors-demo"
[ -f "$demo/tree_model/tree01.txt" ] || { echo "demo: $demo/tree_model/tree01.txt not found (the shared data folder)" >&2; exit 1; }
mkdir -p "$out"
"$simtree" convert "$demo/tree_model/tree01.txt" "$out/tree01.json" --params "$demo/tree_parameters.txt"
"$simtree" mesh "$out/tree01.json" --out "$out/tree01.ply"
"$simtree" mesh "$out/tree01.json" --out "$out/tree01.obj"
"$simtree" info "$out/tree01.json"
# Pull branch 1 (a first-level branch) at its tip with 100 N, hold from 1 s, let go at 3 s.
"$simtree" simulate "$out/tree01.json" --pull 1 --force 100 --hold 1 --release 3 --duration 10 \
  --out "$out/pull"
echo "demo: wrote $out/tree01.json, $out/tree01.ply (Open3D, CloudCompare, MeshLab) and $out/tree01.obj (Blender)"
echo "demo: the pull test is in $out/pull/: animation.glb (Blender, three.js), markers.csv, nodes.bin"
