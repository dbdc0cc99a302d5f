#!/usr/bin/env bash
# Configures and builds the libFuzzer harnesses with clang in their own build directory.
# Usage: build_harnesses.sh <source-dir> <build-dir>   (FUZZ_BUILD_JOBS sets the parallelism, default 2)
set -euo pipefail
source_dir=$1 build_dir=$2
mkdir -p "$build_dir"
cmake -S "$source_dir/tests/fuzz/harnesses" -B "$build_dir" -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$build_dir/configure.log" 2>&1 || {
  cat "$build_dir/configure.log"; echo "FAIL: fuzz harnesses did not configure"; exit 1; }
cmake --build "$build_dir" -j "${FUZZ_BUILD_JOBS:-2}" >"$build_dir/build.log" 2>&1 || {
  cat "$build_dir/build.log"; echo "FAIL: fuzz harnesses did not build"; exit 1; }
ls "$build_dir/bin"
