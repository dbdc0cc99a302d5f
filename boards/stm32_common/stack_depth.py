#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Worst-case stack depth of an STM32 image from GCC's call graphs (-fcallgraph-info=su).

Each object file compiled with -fcallgraph-info=su leaves a .ci file (VCG) with one node per
function (its frame size from -fstack-usage) and one edge per direct call. The depth of a function
is its frame plus the deepest of its callees; the image needs the depth of Reset_Handler (which
runs curvestep_main) plus, for every interrupt handler, its depth and the exception frame the core
stacks on entry (interrupts may nest: all are added). Functions without a call graph (libgcc's
soft-float routines, newlib's sqrt/memcpy: small, 56 bytes at most with their own callees) count
as UNKNOWN_BYTES each,
and so does every indirect call (the fault handlers' report and SysTick's counter callback: small).
Recursion makes the depth unbounded and fails the analysis.

With --elf IMAGE the graphs are checked against the linked image (arm-none-eabi-readelf/objdump):
a callee the graphs name without a frame but that shares its address with a function that has one
(identical code folding makes such aliases) resolves to that function; every direct branch (bl, or
a tail-call b) from a function with a graph to another function's entry that no edge of the graphs
covers is added as an edge (and listed); and the image's functions without a graph are listed and
must be libgcc's and newlib's C routines (a C++ function, a curvestep_* entry point or an interrupt
or exception handler without one fails the analysis). This is what keeps the analysis sound for
link-time-optimised images, whose graphs come from the LTRANS unit instead of the objects
(docs/boards.md).

Usage: stack_depth.py [--fpu] [--elf IMAGE] [--json OUT] [--limit BYTES] CI_FILE...
Prints the depth and the deepest call chain; exits 1 if the depth exceeds --limit.
"""
import argparse
import json
import re
import subprocess
import sys

UNKNOWN_BYTES = 64          # a libgcc/newlib routine or an indirect call (0-56 bytes measured)
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
    # The LTRANS unit of an LTO link labels functions by their short names ("poll.constprop"): name
    # them by their demangled symbols instead (c++filt, if there is one), as the objects' graphs do.
    short = [t for t, name in display.items() if "(" not in name and bare(t).startswith("_Z")]
    if short:
        try:
            out = subprocess.run(["c++filt"], input="\n".join(bare(t) for t in short), capture_output=True,
                                 text=True, check=True).stdout.splitlines()
            if len(out) == len(short):
                display.update(zip(short, out))
        except (OSError, subprocess.CalledProcessError):
            pass
    by_name = {}
    for title in frames:
        by_name.setdefault(bare(title), title)
    return frames, display, calls, by_name, dynamic


def image_functions(elf):
    """{name: [addresses]} of the image's functions (local ones may share a name) and
    {address: [(branch target name, target address)]} of the direct branches out of each."""
    symtab = subprocess.run(["arm-none-eabi-readelf", "-sW", elf], capture_output=True, text=True, check=True)
    functions = {}
    for line in symtab.stdout.splitlines():
        f = line.split()
        if len(f) == 8 and f[3] == "FUNC" and f[6] != "UND":
            functions.setdefault(f[7], []).append(int(f[1], 16) & ~1)
    dis = subprocess.run(["arm-none-eabi-objdump", "-d", "--no-show-raw-insn", elf],
                         capture_output=True, text=True, check=True)
    branches = {}
    current = None
    for line in dis.stdout.splitlines():
        m = re.match(r"^([0-9a-f]+) <[^>]+>:", line)
        if m:
            current = int(m.group(1), 16)
            continue
        m = re.search(r"\tb[a-z]*(?:\.[wn])?\s+([0-9a-f]+) <([^>+]+)>", line)
        if m and current is not None and int(m.group(1), 16) != current:
            branches.setdefault(current, []).append((m.group(2), int(m.group(1), 16)))
    return functions, branches


def check_against_image(elf, frames, calls):
    """Alias resolution, edges from the disassembly and the functions without a graph (see --elf).
    A name at several addresses (local functions of different units) matches all its graph nodes:
    each of its bodies is checked against the edges of all of them, and missing ones go to all."""
    functions, branches = image_functions(elf)
    entries = {address for addresses in functions.values() for address in addresses}
    framed_at = {}
    for title in frames:
        for address in functions.get(bare(title), []):
            framed_at.setdefault(address, []).append(title)
    aliases = {}
    for name, addresses in functions.items():
        titles = {t for address in addresses for t in framed_at.get(address, [])}
        if len(titles) == 1:
            aliases[name] = titles.pop()
    added = []
    for address, titles in framed_at.items():
        callees = [bare(callee) for title in titles for callee in calls.get(title, [])]
        covered = set(callees) | {a for callee in callees for a in functions.get(callee, [])}
        for name, target in branches.get(address, []):
            if target in entries and target not in covered and name not in covered:
                for title in titles:
                    calls.setdefault(title, []).append(name)
                covered.add(target)
                added.append("%s -> %s" % (bare(titles[0]), name))
    without = sorted({name for name, addresses in functions.items()
                      if not any(address in framed_at for address in addresses)})
    ours = [name for name in without if is_project_function(name)]
    if ours:
        raise RuntimeError("no call graph for the image's own function(s) " + ", ".join(ours[:8]) +
                           " (only libgcc's and newlib's C routines may lack one)")
    return aliases, added, without


def is_project_function(symbol):
    """True for a function of this project's code: C++ (mangled; libgcc and newlib are C), a
    curvestep_* entry point, or a handler of the vector table."""
    return symbol.startswith("_Z") or symbol.startswith("curvestep") or symbol.endswith("Handler")


def analyse(files, fpu, elf=None):
    frames, display, calls, by_name, dynamic = load(files)
    aliases, added, without = ({}, None, None)
    if elf:
        aliases, added, without = check_against_image(elf, frames, calls)
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
        return aliases.get(bare(title))

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
    result = {
        "worst_case_bytes": total,
        "main_bytes": main_bytes,
        "interrupt_bytes": interrupts,
        "exception_frame_bytes": frame,
        "deepest_chain": main_chain,
        "assumed_bytes_per_unknown_callee": UNKNOWN_BYTES,
        "unknown_callees": sorted(unknown),
        "dynamic_frames": dynamic,
    }
    if elf:
        result["edges_from_disassembly"] = added
        result["image_functions_without_call_graph"] = without
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("ci", nargs="+")
    parser.add_argument("--fpu", action="store_true", help="Cortex-M4F: extended exception frames")
    parser.add_argument("--elf", help="check the graphs against this linked image (see above)")
    parser.add_argument("--json", help="write the result as JSON")
    parser.add_argument("--limit", type=int, help="fail if the worst case exceeds this many bytes")
    args = parser.parse_args()
    try:
        result = analyse(args.ci, args.fpu, args.elf)
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
