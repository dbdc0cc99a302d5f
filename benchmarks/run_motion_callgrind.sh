#!/usr/bin/env bash
# Instructions per tick of MotionController::next_setpoint, chunked forward differencing against the
# exact per-tick evaluation, counted in ONE callgrind run of motion_interpolation_benchmark.
# Usage: benchmarks/run_motion_callgrind.sh <path to motion_interpolation_benchmark> [rate_hz]
# Collection is toggled on inside bench_ticks_chunked and bench_ticks_exact only (queueing the job
# and printing are not counted); callgrind_annotate gives each function's inclusive count.
set -euo pipefail
binary=${1:?usage: run_motion_callgrind.sh <motion_interpolation_benchmark> [rate_hz]}
rate=${2:-1000}
command -v valgrind >/dev/null || { echo '{"error": "valgrind not installed"}'; exit 1; }
command -v callgrind_annotate >/dev/null || { echo '{"error": "callgrind_annotate not installed"}'; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$work/out" \
  --toggle-collect=bench_ticks_chunked --toggle-collect=bench_ticks_exact \
  "$binary" --rate "$rate" --repetitions 1 >"$work/json" 2>"$work/log"
ticks=$(awk -F': ' '/"ticks_per_run"/ {gsub(/,/, "", $2); print $2}' "$work/json")
callgrind_annotate --inclusive=yes "$work/out" >"$work/annotated"
count() { awk -v f="$1" '$0 ~ (":" f " ") {gsub(/,/, "", $1); print $1; exit}' "$work/annotated"; }
chunked=$(count bench_ticks_chunked)
exact=$(count bench_ticks_exact)
awk -v c="$chunked" -v e="$exact" -v n="$ticks" -v r="$rate" 'BEGIN {
  printf "{\n  \"rate_hz\": %s,\n  \"ticks\": %s,\n", r, n
  printf "  \"instructions_per_tick\": {\"chunked\": %.1f, \"exact\": %.1f},\n", c / n, e / n
  printf "  \"exact_over_chunked\": %.2f\n}\n", e / c
}'
