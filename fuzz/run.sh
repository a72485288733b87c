#!/usr/bin/env bash
# Runs every fuzz target (or those named) for a set time on its seed corpus:
#   fuzz/run.sh <fuzz build folder> [target ...]
# FUZZ_SECONDS per target (default 60), FUZZ_JOBS targets at once (default 1), SHARED data folder
# for the seeds that are real files (default ../shared/data). The corpora grow in
# <build>/fuzz_corpus/<target>; crashes, hangs and sanitizer reports are kept as
# <build>/fuzz_out/<target>-crash-*, -timeout-*, -oom-* with the log in <build>/fuzz_out/<target>.log.
# Exits non-zero when any target found something; prints one line per target either way.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: fuzz/run.sh <fuzz build folder> [target ...]}
shift
seconds=${FUZZ_SECONDS:-60}
jobs=${FUZZ_JOBS:-1}
shared=${SHARED:-$(cd .. && pwd)/shared}/data

# Largest input per target (bytes): a little over the largest real file of its kind that the
# seeds hold, so the fuzzer spends its time on structure, not on size.
declare -A max_len=(
  [tree_json]=16384 [legacy_tree]=65536 [legacy_parameters]=4096 [materials_json]=32768
  [markers_json]=4096 [trajectories_csv]=16384 [intrinsics_json]=2048 [capture_files]=4096
  [azure_calibration]=16384 [point_cloud_xyz]=8192 [point_cloud_ply]=8192
  [point_cloud_pcd]=8192 [png_image]=16384 [azure_mkv]=262144 [point_cloud_las]=4096
  [realsense_bag]=16384 [tum_list]=2048 [open3d_intrinsic]=2048
)
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(tree_json legacy_tree legacy_parameters materials_json
  markers_json trajectories_csv intrinsics_json capture_files azure_calibration point_cloud_xyz
  point_cloud_ply point_cloud_pcd png_image azure_mkv point_cloud_las realsense_bag tum_list
  open3d_intrinsic)

corpus=$build/fuzz_corpus
out=$build/fuzz_out
mkdir -p "$corpus" "$out"
"$build/bin/simtree_fuzz_seeds" "$corpus" "$shared"

# One target: libFuzzer with ASan+UBSan (built in), a hang is an input over 10 s, a memory
# blowup a process over 2 GB or one allocation over 1 GB (a header claiming a billion points).
run_one() {
  local t=$1
  local log=$out/$t.log
  rm -f "$out/$t"-{crash,timeout,oom,leak,slow-unit}-*
  # The inputs of past findings (fuzz/regressions/<target>/, each also a regression test) are
  # read as seeds, so a fix that regresses shows at once.
  local seeds=()
  [ -d "fuzz/regressions/$t" ] && seeds=("fuzz/regressions/$t")
  if ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/bin/fuzz_$t" "$corpus/$t" "${seeds[@]}" -max_total_time="$seconds" -max_len="${max_len[$t]}" \
      -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -print_final_stats=1 \
      -artifact_prefix="$out/$t-" >"$log" 2>&1; then
    local runs cov
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
    echo "fuzz $t: ok, ${seconds} s, ${runs:-?} runs, ${cov:-?} edges, $(ls "$corpus/$t" | wc -l) corpus files"
  else
    echo "fuzz $t: FOUND a problem, see $log and $out/$t-*"
    grep -m3 -E 'ERROR: |runtime error|uncaught|terminate' "$log" | sed 's/^/  /' || true
    return 1
  fi
}

failed=0
running=0
for t in "${targets[@]}"; do
  [ -n "${max_len[$t]:-}" ] || { echo "fuzz: no target \"$t\"" >&2; exit 2; }
  run_one "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=1
  running=$((running - 1))
done
exit $failed
