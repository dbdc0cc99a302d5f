#!/usr/bin/env bash
# Counts instructions per setpoint of each method of forward_difference_benchmark under callgrind.
# Usage: benchmarks/run_callgrind.sh <path to forward_difference_benchmark> [steps]
# Prints JSON: instructions per point for every method (collection is toggled on inside the
# function bench_<method> only, so start-up and printing are not counted) and the ratios.
set -euo pipefail
binary=${1:?usage: run_callgrind.sh <forward_difference_benchmark> [steps]}
steps=${2:-100000}
command -v valgrind >/dev/null || { echo '{"error": "valgrind not installed"}'; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
methods="forward_difference_q16_16 forward_difference_float de_casteljau_q16_16 de_casteljau_float horner_q16_16 horner_float"
declare -A per_point
for method in $methods; do
  out="$work/$method.out"
  valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect="bench_$method" \
    "$binary" --steps "$steps" --repetitions 1 --method "$method" >/dev/null 2>"$work/$method.log"
  instructions=$(awk '/^(summary|totals):/ {print $2; exit}' "$out")
  per_point[$method]=$(awk -v i="$instructions" -v n="$steps" 'BEGIN {printf "%.1f", i / (n + 1)}')
done
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.2f", a / b}'; }
printf '{\n  "steps": %s,\n  "instructions_per_point": {\n' "$steps"
first=1
for method in $methods; do
  [ $first -eq 1 ] || printf ',\n'
  first=0
  printf '    "%s": %s' "$method" "${per_point[$method]}"
done
printf '\n  },\n  "de_casteljau_over_forward_difference": {\n'
printf '    "q16_16": %s,\n' "$(ratio "${per_point[de_casteljau_q16_16]}" "${per_point[forward_difference_q16_16]}")"
printf '    "float": %s\n  },\n' "$(ratio "${per_point[de_casteljau_float]}" "${per_point[forward_difference_float]}")"
printf '  "horner_over_forward_difference": {\n'
printf '    "q16_16": %s,\n' "$(ratio "${per_point[horner_q16_16]}" "${per_point[forward_difference_q16_16]}")"
printf '    "float": %s\n  }\n}\n' "$(ratio "${per_point[horner_float]}" "${per_point[forward_difference_float]}")"
