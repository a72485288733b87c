#!/usr/bin/env bash
# Runs every benchmark executable of a build and keeps their JSON results in <build>/bench-results/.
# usage: bench/run.sh <build folder> [benchmark name filter]
set -euo pipefail
build=${1:-build-bench}
filter=${2:-}
results="$build/bench-results"
mkdir -p "$results"
echo "bench: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
for exe in "$build"/bin/bench_*; do
  [ -x "$exe" ] || continue
  name=$(basename "$exe")
  [ -z "$filter" ] || [[ "$name" == *"$filter"* ]] || continue
  echo "== $name"
  "$exe" --benchmark_out="$results/$name.json" --benchmark_out_format=json
done
