#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Worst-case stack depth of an STM32 image from GCC's call graphs (-fcallgraph-info=su).

Each object file compiled with -fcallgraph-info=su leaves a .ci file (VCG) with one node per
function (its frame size from -fstack-usage) and one edge per direct call. The depth of a function
is its frame plus the deepest of its callees; the image needs the depth of Reset_Handler (which
runs curvestep_main) plus, for every interrupt handler, its depth and the exception frame the core
stacks on entry (interrupts may nest: all are added). Functions without a call graph (libgcc's
soft-float routines, newlib's sqrt/memcpy: leaves with small frames) count as UNKNOWN_BYTES each,
and so does every indirect call (the fault handlers' report and SysTick's counter callback: small).
Recursion makes the depth unbounded and fails the analysis.

Usage: stack_depth.py [--fpu] [--json OUT] [--limit BYTES] CI_FILE...
Prints the depth and the deepest call chain; exits 1 if the depth exceeds --limit.
"""
import argparse
import json
import re
import sys

UNKNOWN_BYTES = 64          # a libgcc/newlib leaf or an indirect call (they use 0-40 bytes)
FRAME_BYTES = 32            # basic exception frame: r0-r3, r12, lr, pc, xpsr (+ 4 bytes alignment worst case)
FPU_FRAME_BYTES = 104       # extended frame with s0-s15 and FPSCR (Cortex-M4F, lazy stacking reserves it)
INTERRUPTS = ("SysTick_Handler", "USART1_IRQHandler", "TIM2_IRQHandler")

node_re = re.compile(r'^node: \{ title: "([^"]*)" label: "([^"]*)"')
edge_re = re.compile(r'^edge: \{ sourcename: "([^"]*)" targetname: "([^"]*)"')
bytes_re = re.compile(r'\\n(\d+) bytes \((static|dynamic|dynamic,bounded)\)')


def bare(title):
    return title.rsplit(":", 1)[-1]


def load(files):
    frames = {}   # title -> bytes (defined functions only)
    display = {}  # title -> readable name
    calls = {}    # title -> [callee titles]
    dynamic = []
    for path in files:
        with open(path, encoding="utf-8", errors="replace") as f:
            for line in f:
                m = node_re.match(line)
                if m:
                    title, label = m.groups()
                    display.setdefault(title, label.split("\\n", 1)[0])
                    b = bytes_re.search(label)
                    if b:
                        frames[title] = int(b.group(1))
                        if b.group(2) != "static":
                            dynamic.append(label.split("\\n", 1)[0])
                    continue
                m = edge_re.match(line)
                if m:
                    calls.setdefault(m.group(1), []).append(m.group(2))
    by_name = {}
    for title in frames:
        by_name.setdefault(bare(title), title)
    return frames, display, calls, by_name, dynamic


def analyse(files, fpu):
    frames, display, calls, by_name, dynamic = load(files)
    unknown = set()
    memo = {}
    active = set()

    def resolve(title):
        if title in frames:
            return title
        for candidate in (title, re.sub(r"([CD])1(E|I)", r"\g<1>2\2", title)):  # complete -> base constructor
            if candidate in frames:
                return candidate
            if bare(candidate) in by_name:
                return by_name[bare(candidate)]
        return None

    def depth(title):
        """(bytes, chain) of the deepest path from the function `title`."""
        if title in memo:
            return memo[title]
        if title in active:
            raise RuntimeError("recursion through " + display.get(title, title))
        active.add(title)
        best = (0, [])
        for callee in calls.get(title, []):
            target = resolve(callee)
            if target is None:
                name = display.get(callee, bare(callee))
                unknown.add(name)
                candidate = (UNKNOWN_BYTES, [name + " (assumed %d)" % UNKNOWN_BYTES])
            else:
                candidate = depth(target)
            if candidate[0] > best[0]:
                best = candidate
        active.discard(title)
        result = (frames[title] + best[0], ["%s (%d)" % (display.get(title, title), frames[title])] + best[1])
        memo[title] = result
        return result

    reset = by_name.get("Reset_Handler")
    if reset is None:
        raise RuntimeError("no Reset_Handler in the call graphs")
    main_bytes, main_chain = depth(reset)
    frame = FPU_FRAME_BYTES if fpu else FRAME_BYTES
    interrupts = {}
    for name in INTERRUPTS:
        title = by_name.get(name)
        if title is not None:
            interrupts[name] = depth(title)[0] + frame
    total = main_bytes + sum(interrupts.values())
    return {
        "worst_case_bytes": total,
        "main_bytes": main_bytes,
        "interrupt_bytes": interrupts,
        "exception_frame_bytes": frame,
        "deepest_chain": main_chain,
        "assumed_bytes_per_unknown_callee": UNKNOWN_BYTES,
        "unknown_callees": sorted(unknown),
        "dynamic_frames": dynamic,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("ci", nargs="+")
    parser.add_argument("--fpu", action="store_true", help="Cortex-M4F: extended exception frames")
    parser.add_argument("--json", help="write the result as JSON")
    parser.add_argument("--limit", type=int, help="fail if the worst case exceeds this many bytes")
    args = parser.parse_args()
    try:
        result = analyse(args.ci, args.fpu)
    except RuntimeError as e:
        print("FAIL: stack analysis:", e)
        return 1
    if args.limit is not None:
        result["limit_bytes"] = args.limit
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(result, f, indent=1)
    print("worst-case stack %d bytes (main %d, interrupts %s)" % (
        result["worst_case_bytes"], result["main_bytes"],
        ", ".join("%s %d" % kv for kv in result["interrupt_bytes"].items())))
    print("deepest chain: " + " -> ".join(result["deepest_chain"]))
    if result["dynamic_frames"]:
        print("FAIL: dynamic stack frames (alloca/VLA):", ", ".join(result["dynamic_frames"]))
        return 1
    if args.limit is not None and result["worst_case_bytes"] > args.limit:
        print("FAIL: worst-case stack %d bytes exceeds the reserved %d" % (result["worst_case_bytes"], args.limit))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
