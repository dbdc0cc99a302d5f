#!/usr/bin/env bash
# Runs one libFuzzer harness for a bounded time: first every committed seed and regression input,
# then new inputs for <seconds>. Fails on any crash, sanitizer report, leak or timeout.
# Usage: run_harness.sh <harness> <seconds> <source-dir> <build-dir> [extra libFuzzer flags...]
# New inputs go to <build-dir>/work/<harness> (never into the committed corpus); a crashing input is
# saved as <build-dir>/artifacts/<harness>-crash-<sha1>.
set -euo pipefail
harness=$1 seconds=$2 source_dir=$3 build_dir=$4
shift 4
binary="$build_dir/bin/${harness}_fuzz"
[ -x "$binary" ] || { echo "FAIL: $binary not built (run build_harnesses.sh)"; exit 1; }
work="$build_dir/work/$harness"
mkdir -p "$work" "$build_dir/artifacts"
inputs=("$work" "$source_dir/tests/fuzz/corpus/$harness")
[ -d "$source_dir/tests/fuzz/regressions/$harness" ] && inputs+=("$source_dir/tests/fuzz/regressions/$harness")
dict=()
[ -f "$source_dir/tests/fuzz/dictionaries/$harness.dict" ] && dict=(-dict="$source_dir/tests/fuzz/dictionaries/$harness.dict")
exec "$binary" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$build_dir/artifacts/$harness-" "${dict[@]}" "$@" "${inputs[@]}"
