#!/usr/bin/env bash
# Checks a linked STM32 image: prints text/data/bss, fails when it references heap or exception
# machinery (the symbol list of tests/embedded/check_allocation_free.sh) or exceeds its budget.
# Usage: check_image.sh <image.elf> <flash-limit-bytes> <ram-limit-bytes>
set -euo pipefail
elf=$1 flash_limit=$2 ram_limit=$3
forbidden='^(malloc|free|calloc|realloc|_malloc_r|_free_r|_calloc_r|_realloc_r|_Znwj|_Znaj|_ZdlPv|_ZdaPv|_ZdlPvj|_ZdaPvj|_ZnwjRKSt9nothrow_t|__cxa_throw|__cxa_allocate_exception|__cxa_begin_catch|__gxx_personality_v0|_Unwind_Resume)$'
arm-none-eabi-size "$elf"
read -r text data bss _ < <(arm-none-eabi-size "$elf" | tail -n 1)
hits=$(arm-none-eabi-nm "$elf" | awk '{print $NF}' | grep -E "$forbidden" || true)
if [ -n "$hits" ]; then
  echo "FAIL: $elf references heap or exception support:" $hits
  exit 1
fi
# size's bss column already includes the reserved stack (.stack, NOLOAD).
stack=$(arm-none-eabi-size -A "$elf" | awk '$1 == ".stack" {print $2}')
flash=$((text + data)) ram=$((data + bss))
echo "$(basename "$elf"): flash $flash / $flash_limit bytes, RAM $ram / $ram_limit bytes (stack ${stack:-0} included)"
if [ "$flash" -gt "$flash_limit" ] || [ "$ram" -gt "$ram_limit" ]; then
  echo "FAIL: $(basename "$elf") exceeds its budget"
  exit 1
fi
echo "PASS: $(basename "$elf") is free of malloc/free/operator new/delete/exceptions and within budget"
