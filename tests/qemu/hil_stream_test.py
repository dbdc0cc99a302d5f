#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""HIL test against an emulated board: the App<Board> firmware runs in QEMU with USART1 on a
pseudo-terminal, `curvestep stream` uploads a job to it and captures its setpoint stream, and the
stream is compared with `curvestep sim` of the same job, planned with the device's look-ahead
(from its Capabilities, as `curvestep stream` prints it): bit-identical (--exact, fixed point) or
within a tolerance in mm (float firmware). Exit 77 (skipped) when this curvestep has no `stream`.
Usage: hil_stream_test.py <stm32f1|stm32f4> <firmware.elf> <curvestep> <job.json> <machine.json>
                          (--exact | --tolerance MM)"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from qemu_board import MACHINES, QemuBoard, curvestep_can_stream  # noqa: E402



def read_csv(path):
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def main():
    parser = argparse.ArgumentParser()
    for name in ("board", "elf", "curvestep", "job", "machine"):
        parser.add_argument(name)
    group = parser.add_mutually_exclusive_group(required=True)
    group.add_argument("--exact", action="store_true")
    group.add_argument("--tolerance", type=float)
    parser.add_argument("--round-weights", action="store_true",
                        help="send a copy of the job with its weights rounded to Q16.16 (the wire's format), "
                             "so that it means the same to sim and to the device")
    args = parser.parse_args()
    if not curvestep_can_stream(args.curvestep):
        return 77
    with tempfile.TemporaryDirectory(prefix="curvestep-hil-") as work:
        capture, simulated = os.path.join(work, "device.csv"), os.path.join(work, "sim.csv")
        if args.round_weights:
            with open(args.job, encoding="utf-8") as handle:
                job = json.load(handle)
            for segment in job["segments"]:
                if "weights" in segment:
                    segment["weights"] = [round(w * 65536.0) / 65536.0 for w in segment["weights"]]
            args.job = os.path.join(work, "wire_exact_job.json")
            with open(args.job, "w", encoding="utf-8") as handle:
                json.dump(job, handle)
        with QemuBoard(MACHINES[args.board], args.elf, open_pty=False, wall_limit=120) as board:
            stream = subprocess.run([args.curvestep, "stream", args.job, "--machine", args.machine, "--port", board.pty,
                                     "--capture", capture], capture_output=True, text=True, timeout=100)
        print(stream.stdout + stream.stderr)
        if stream.returncode != 0:
            print(f"FAIL: curvestep stream exited with {stream.returncode}")
            return 1
        # The device's planning window (its Capabilities, printed by stream): sim plans with the same.
        # A device without a planner replays what stream planned with its --lookahead (default 16).
        # Planned here without --lookahead: the distance window, as curvestep sim plans without it.
        lookahead = (re.search(r"device look-ahead:\s+(\d+)", stream.stdout) or
                     re.search(r"planned here with --lookahead (\d+)", stream.stdout))
        by_distance = "planned here with the distance window" in stream.stdout
        if lookahead is None and not by_distance:
            print("FAIL: curvestep stream did not print the device's look-ahead")
            return 1
        window = [] if by_distance else ["--lookahead", lookahead.group(1)]
        sim = subprocess.run([args.curvestep, "sim", args.job, "-m", args.machine, "-o", simulated] + window,
                             capture_output=True, text=True, timeout=100)
        if sim.returncode != 0:
            print("FAIL: curvestep sim failed:", sim.stdout + sim.stderr)
            return 1
        device, reference = read_csv(capture), read_csv(simulated)
    if len(device) != len(reference) or not device:
        print(f"FAIL: {len(device)} setpoints from the device, {len(reference)} from sim")
        return 1
    worst, identical = 0.0, 0
    for index, (d, r) in enumerate(zip(device, reference)):
        if d["t"] != r["t"]:
            print(f"FAIL: setpoint {index} at t={d['t']} on the device, t={r['t']} in sim")
            return 1
        same = all(d[axis] == r[axis] for axis in "xyz")
        identical += same
        worst = max(worst, max(abs(float(d[axis]) - float(r[axis])) for axis in "xyz"))
        if args.exact and not same:
            print(f"FAIL: setpoint {index} differs: device {d} sim {r}")
            return 1
    print(f"{len(device)} setpoints, {identical} bit-identical, largest difference {worst:.9g} mm")
    if args.tolerance is not None and worst > args.tolerance:
        print(f"FAIL: difference above the tolerance {args.tolerance} mm")
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
