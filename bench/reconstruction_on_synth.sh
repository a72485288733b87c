#!/usr/bin/env bash
# Static reconstruction on synthetic captures, scored against the true tree (issue 7's
# acceptance): for every species and seed, `simtree synth` makes a capture (skipped when it is
# there already), then bench_reconstruction merges each capture's scan views with the true camera
# poses, reconstructs the tree and scores it against gt/tree.json (branches with radius >= 1 cm).
# Prints one markdown row per capture and the means.
#
# usage: bench/reconstruction_on_synth.sh <build folder> <work folder> [seeds] [species...]
#   e.g. bench/reconstruction_on_synth.sh build /tmp/rec "1 2 3"
# (the build folder configured with -DSIMTREE_BUILD_BENCH=ON: bin/simtree, bin/bench_reconstruction)
# Pictures of each model over its cloud, and of the true tree, go to <work folder>/pictures.
set -euo pipefail
build=$1
work=$2
seeds=${3:-"1 2 3"}
shift $(( $# >= 3 ? 3 : $# ))
species=${*:-"acer_palmatum magnolia acer_rubrum"}
mkdir -p "$work/pictures"

captures=()
for sp in $species; do
  for seed in $seeds; do
    scene="$work/${sp}_$seed"
    # A 4.5 s pull stream at 1 fps: the static scans and the tree are the same bytes as the
    # default capture's (their random streams do not depend on the pull), in a tenth of the time.
    [ -f "$scene/gt/tree.json" ] || "$build/bin/simtree" -q synth --species "$sp" --seed "$seed" \
      --duration 4.5 --fps 1 --no-contact-sheet --out "$scene" > /dev/null
    captures+=("$scene")
  done
done
"$build/bin/bench_reconstruction" --synth --pictures "$work/pictures" "${captures[@]}"
