#!/usr/bin/env bash
# Cross-builds the allocation probe for one Cortex-M core and fails if the image references
# heap or exception machinery. Prints the image's text/data/bss sizes.
# Usage: check_allocation_free.sh <cortex-m3|cortex-m4f> <source-dir> <build-dir>
set -euo pipefail
cpu=$1 source_dir=$2 build_dir=$3
cmake -S "$source_dir" -B "$build_dir" -DCMAKE_TOOLCHAIN_FILE="$source_dir/cmake/toolchains/arm-none-eabi-gcc.cmake" \
  -DCURVESTEP_CPU="$cpu" -DCMAKE_BUILD_TYPE=MinSizeRel -DCURVESTEP_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build "$build_dir" --target curvestep_probe -j 2 >"$build_dir/probe_build.log" 2>&1 || {
  cat "$build_dir/probe_build.log"; echo "FAIL: probe for $cpu did not build"; exit 1; }
elf="$build_dir/bin/curvestep_probe.elf"
forbidden='^(malloc|free|calloc|realloc|_malloc_r|_free_r|_calloc_r|_realloc_r|_Znwj|_Znaj|_ZdlPv|_ZdaPv|_ZdlPvj|_ZdaPvj|_ZnwjRKSt9nothrow_t|__cxa_throw|__cxa_allocate_exception|__cxa_begin_catch|__gxx_personality_v0|_Unwind_Resume)$'
hits=$(arm-none-eabi-nm "$elf" | awk '{print $NF}' | grep -E "$forbidden" || true)
arm-none-eabi-size "$elf"
if [ -n "$hits" ]; then
  echo "FAIL: $cpu probe image references heap or exception support:"
  echo "$hits"
  exit 1
fi
echo "PASS: $cpu probe image is free of malloc/free/operator new/delete/exceptions"
