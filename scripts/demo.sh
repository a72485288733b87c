#!/usr/bin/env bash
# The demo: the paper's authors' tree01 with its material parameters becomes a simtree JSON tree
# and a generalized-cylinder mesh, and simtree prints what it holds.
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
echo "demo: wrote $out/tree01.json, $out/tree01.ply (Open3D, CloudCompare, MeshLab) and $out/tree01.obj (Blender)"
