#!/usr/bin/env bash
# Checks a linked STM32 image: prints text/data/bss and the worst-case stack, writes the figures as
# JSON, and fails when the image references heap or exception machinery (the symbol list of
# tests/embedded/check_allocation_free.sh), exceeds its flash/RAM budget, or (policy "enforce")
# needs more stack than its linker script reserves.
# Usage: check_image.sh <image.elf> <flash-limit> <ram-limit> <enforce|report> <fpu|nofpu>
#                       <goal-flash> <goal-ram> <out.json> <call-graph-dir>...
# (limits in bytes; goal 0 0: none; the call-graph dirs hold the .ci files of -fcallgraph-info=su: the
# objects' or, for an LTO image, the LTRANS unit's; stack_depth.py checks them against the image, --elf)
set -euo pipefail
elf=$1 flash_limit=$2 ram_limit=$3 stack_policy=$4 fpu=$5 goal_flash=$6 goal_ram=$7 json=$8
shift 8
here=$(cd "$(dirname "$0")" && pwd)
name=$(basename "$elf")
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
stack=${stack:-0}
flash=$((text + data)) ram=$((data + bss))
static_ram=$((ram - stack))
echo "$name: flash $flash / $flash_limit bytes, RAM $ram / $ram_limit bytes (stack $stack included)"

# Worst-case stack from the call graphs (needs python3; without it the figure is left out).
worst=null
stack_json=$(mktemp)
stack_text=$(mktemp)
trap 'rm -f "$stack_json" "$stack_text"' EXIT
if command -v python3 >/dev/null 2>&1; then
  cis=()
  for dir in "$@"; do
    while IFS= read -r f; do cis+=("$f"); done < <(find "$dir" -name '*.ci' 2>/dev/null)
  done
  fpu_flag=()
  [ "$fpu" = fpu ] && fpu_flag=(--fpu)
  if [ ${#cis[@]} -gt 0 ]; then
    if python3 "$here/stack_depth.py" "${fpu_flag[@]}" --elf "$elf" --json "$stack_json" "${cis[@]}" >"$stack_text"; then
      worst=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["worst_case_bytes"])' "$stack_json")
      echo "$name: $(head -n 1 "$stack_text")"
    else
      cat "$stack_text"
      echo "FAIL: $name: stack analysis failed"
      exit 1
    fi
  fi
fi

status=0
if [ "$flash" -gt "$flash_limit" ] || [ "$ram" -gt "$ram_limit" ]; then
  echo "FAIL: $name exceeds its budget"
  status=1
fi
stack_ok=true
if [ "$worst" != null ] && [ "$worst" -gt "$stack" ]; then
  stack_ok=false
  if [ "$stack_policy" = enforce ]; then
    echo "FAIL: $name needs $worst bytes of stack (worst case) and its script reserves $stack"
    status=1
  else
    echo "WARNING: $name needs $worst bytes of stack (worst case) and its script reserves $stack: it would overflow"
  fi
fi
goal_json=null
if [ "$goal_flash" -gt 0 ]; then
  needed_ram=$ram
  [ "$worst" != null ] && needed_ram=$((static_ram + worst))
  met=false
  [ "$flash" -le "$goal_flash" ] && [ "$needed_ram" -le "$goal_ram" ] && met=true
  goal_json="{\"flash_bytes\": $goal_flash, \"ram_bytes\": $goal_ram, \"met\": $met}"
  echo "$name: goal $goal_flash / $goal_ram bytes (flash / RAM with the worst-case stack): $([ $met = true ] && echo met || echo "not met (flash $flash, RAM $needed_ram)")"
fi
ram_needed=null
[ "$worst" != null ] && ram_needed=$((static_ram + worst))
cat > "$json" <<JSON
{
 "image": "$name",
 "flash_bytes": $flash,
 "flash_limit_bytes": $flash_limit,
 "ram_bytes": $ram,
 "ram_limit_bytes": $ram_limit,
 "static_ram_bytes": $static_ram,
 "stack_reserved_bytes": $stack,
 "stack_worst_case_bytes": $worst,
 "ram_with_worst_case_stack_bytes": $ram_needed,
 "stack_fits": $stack_ok,
 "stack_policy": "$stack_policy",
 "goal": $goal_json,
 "stack_analysis": $([ -s "$stack_json" ] && cat "$stack_json" || echo null)
}
JSON
if [ "$status" -eq 0 ]; then
  if [ "$stack_ok" = true ]; then
    echo "PASS: $name is free of malloc/free/operator new/delete/exceptions and within budget"
  else
    echo "PASS: $name is free of malloc/free/operator new/delete/exceptions and within its flash/RAM limits (stack: see the warning)"
  fi
fi
exit $status
