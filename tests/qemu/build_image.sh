#!/usr/bin/env bash
# Cross-builds the images of one STM32 board for the QEMU tests (the stm32f1/stm32f4 preset's settings).
# Usage: build_image.sh <stm32f1|stm32f4|stm32f2-m3> <source-dir> <build-dir> [-DNAME=VALUE]... <target>...
# (-D arguments go to the configure step, e.g. -DCURVESTEP_TICK_PROFILE=ON for the real-time benchmark).
# stm32f2-m3: the stm32f4 board code for a Cortex-M3 STM32F2 with Q16.16 setpoints (QEMU netduino2).
set -euo pipefail
board=$1 source_dir=$2 build_dir=$3
shift 3
defines=()
while [[ $# -gt 0 && $1 == -D* ]]; do defines+=("$1"); shift; done
case $board in
  stm32f1) cpu=cortex-m3 ;;
  stm32f4) cpu=cortex-m4f ;;
  stm32f2-m3) cpu=cortex-m3 board=stm32f4 ;;
  *) echo "unknown board $board"; exit 2 ;;
esac
cmake -S "$source_dir" -B "$build_dir" -DCMAKE_TOOLCHAIN_FILE="$source_dir/cmake/toolchains/arm-none-eabi-gcc.cmake" \
  -DCURVESTEP_CPU="$cpu" -DCURVESTEP_BOARD="$board" -DCMAKE_BUILD_TYPE=MinSizeRel -DCURVESTEP_WARNINGS_AS_ERRORS=ON "${defines[@]}" >/dev/null
for target in "$@"; do
  cmake --build "$build_dir" --target "$target" -j 1 >"$build_dir/$target.log" 2>&1 || {
    cat "$build_dir/$target.log"; echo "FAIL: $target for $board did not build"; exit 1; }
  grep -E "^(PASS|FAIL)|flash .* RAM" "$build_dir/$target.log" || true
done
