#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Deterministic instruction counts of the STM32 benchmark images in QEMU 7.2.

QEMU 7.2 in Debian ships no TCG plugins, and -icount only scales virtual time, so the count comes
from an instruction trace: -singlestep makes every translation block one guest instruction and
-d exec,nochain logs each executed block with its guest PC. The benchmark image calls
curvestep_bench_mark(id) around every region; the number of trace lines between two consecutive
mark entries, minus the empty region's count (the marks' own call overhead), is the region's
instruction count. Counts are of executed (issued) Thumb instructions, not cycles.

Usage: count_instructions.py <stm32f1|stm32f4> <bench.elf> [--json out.json]"""
import argparse
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

MACHINES = {"stm32f1": "stm32vldiscovery", "stm32f4": "netduinoplus2"}


def symbol_address(elf, name):
    for line in subprocess.run(["arm-none-eabi-nm", elf], capture_output=True, text=True, check=True).stdout.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[2] == name:
            return int(parts[0], 16) & ~1
    raise SystemExit(f"{name} not found in {elf}")


def run_trace(board, elf, workdir, wall_limit=120.0):
    uart, trace = os.path.join(workdir, "uart.txt"), os.path.join(workdir, "exec.log")
    command = ["qemu-system-arm", "-M", MACHINES[board], "-display", "none", "-monitor", "none",
               "-serial", f"file:{uart}", "-singlestep", "-d", "exec,nochain", "-D", trace, "-kernel", elf]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, start_new_session=True)
    deadline = time.monotonic() + wall_limit
    try:
        while True:
            if os.path.exists(uart):
                with open(uart, "rb") as handle:
                    if b"bench done" in handle.read():
                        break
            if process.poll() is not None:
                raise SystemExit("qemu exited early: " + process.stderr.read().decode(errors="replace"))
            if time.monotonic() > deadline:
                raise SystemExit("benchmark did not finish within the time limit")
            time.sleep(0.2)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
        process.wait()
    with open(uart, "rb") as handle:
        return handle.read().decode(errors="replace"), trace


def count_regions(trace, mark):
    """Trace-line index of every entry into the mark function, in order."""
    pattern = re.compile(r"^Trace \d+: \S+ \[[0-9a-f]+/([0-9a-f]+)/")
    entries, index, previous_in_mark = [], 0, False
    with open(trace, encoding="ascii", errors="replace") as handle:
        for line in handle:
            match = pattern.match(line)
            if not match:
                continue
            pc = int(match.group(1), 16)
            if pc == mark and not previous_in_mark:
                entries.append(index)
            previous_in_mark = pc == mark
            index += 1
    return entries


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("board", choices=sorted(MACHINES))
    parser.add_argument("elf")
    parser.add_argument("--json")
    parser.add_argument("--label", default="", help="free text stored in the report (e.g. the optimisation level)")
    args = parser.parse_args()
    mark = symbol_address(args.elf, "curvestep_bench_mark")
    with tempfile.TemporaryDirectory(prefix="curvestep-bench-") as workdir:
        uart, trace = run_trace(args.board, args.elf, workdir)
        entries = count_regions(trace, mark)
    results = []
    for line in uart.splitlines():
        match = re.match(r"bench (\S+) index=(\d+) fd_steps=(\d+) steady_steps=(\d+) reseed_interval=(\d+) "
                         r"fd_checksum=(-?\d+) dc_points=(\d+) dc_checksum=(-?\d+)", line.strip())
        if not match:
            continue
        label, index = match.group(1), int(match.group(2))
        steps, steady, interval = int(match.group(3)), int(match.group(4)), int(match.group(5))
        fd_checksum, points, dc_checksum = int(match.group(6)), int(match.group(7)), int(match.group(8))
        first = 12 * (index - 1)  # twelve marks per scalar type, in order
        if len(entries) < first + 12:
            raise SystemExit(f"found {len(entries)} mark entries, expected at least {first + 12}")
        e = entries[first:first + 12]
        overhead = e[1] - e[0]
        fd_steady = e[3] - e[2] - overhead
        fd = fd_steady + e[5] - e[4] - overhead
        dc = e[7] - e[6] - overhead
        step_only = e[9] - e[8] - overhead
        step_point = e[11] - e[10] - overhead
        results.append({
            "scalar": label,
            "forward_difference": {"setpoints": steps, "reseed_interval": interval, "instructions": fd,
                                   "instructions_per_setpoint": round(fd / steps, 2),
                                   "steady_setpoints": steady,
                                   "steady_instructions_per_setpoint": round(fd_steady / steady, 2)
                                   if steady < interval else None,
                                   "steady_step_only_per_setpoint": round(step_only / steady, 2)
                                   if steady < interval else None,
                                   "steady_step_and_point_per_setpoint": round(step_point / steady, 2)
                                   if steady < interval else None,
                                   "checksum": fd_checksum},
            "de_casteljau": {"setpoints": points, "instructions": dc,
                             "instructions_per_setpoint": round(dc / points, 2),
                             "checksum": dc_checksum},
            "ratio": round((dc / points) / (fd / steps), 1),
        })
    if not results:
        raise SystemExit("no benchmark lines on the UART:\n" + uart)
    report = {"board": args.board, "machine": MACHINES[args.board], "qemu": "7.2", "method":
              "qemu -singlestep -d exec,nochain: trace lines between curvestep_bench_mark entries minus the empty region",
              "image": os.path.basename(args.elf), "label": args.label, "curve": "3-axis cubic (0,0,0) (250,400,30) (750,-400,60) (1000,0,100) mm",
              "results": results}
    text = json.dumps(report, indent=2)
    print(text)
    if args.json:
        with open(args.json, "w", encoding="utf-8") as handle:
            handle.write(text + "\n")


if __name__ == "__main__":
    sys.exit(main())
