#!/usr/bin/env bash
# The longer fuzz run (docs/robustness.md): builds the libFuzzer harnesses with clang and runs each
# one for a while, then prints libFuzzer's coverage and speed per harness.
# Usage: scripts/fuzz.sh [seconds per harness, default 300] [harness ...]
#   harnesses: message link job machine planner gcode svg (default: all)
#   FUZZ_BUILD_DIR  build directory (default build/fuzz)
#   FUZZ_MERGE=1    afterwards, merge the new inputs that add coverage into tests/fuzz/corpus/<harness>
# Crashing inputs are saved as $FUZZ_BUILD_DIR/artifacts/<harness>-crash-*: add each to
# tests/fuzz/regressions/<harness>/ with the fix, so CTest replays it from then on.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
seconds=${1:-300}
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -eq 0 ] && harnesses=(message link job machine planner gcode svg)
build=${FUZZ_BUILD_DIR:-$root/build/fuzz}

tests/fuzz/build_harnesses.sh "$root" "$build" >/dev/null
status=0
for h in "${harnesses[@]}"; do
  log="$build/$h.log"
  echo "== $h: $seconds s (log: $log)"
  if tests/fuzz/run_harness.sh "$h" "$seconds" "$root" "$build" >"$log" 2>&1; then
    grep -E '^#[0-9]+[[:space:]]+DONE' "$log" || true
    grep -E 'stat::(number_of_executed_units|peak_rss_mb)' "$log" || true
  else
    status=1
    echo "FINDING in $h:"
    grep -E 'ERROR|finding|runtime error|Test unit written' "$log" || tail -20 "$log"
  fi
  if [ "${FUZZ_MERGE:-0}" = 1 ]; then
    "$build/bin/${h}_fuzz" -merge=1 "tests/fuzz/corpus/$h" "$build/work/$h" >"$build/$h.merge.log" 2>&1
    echo "   merged: $(ls "tests/fuzz/corpus/$h" | wc -l) corpus files"
  fi
done
exit $status
