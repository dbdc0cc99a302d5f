#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Step/dir output of the STM32 firmware in QEMU: the App<Board> firmware runs a real job streamed
by `curvestep stream`, its TIM2 interrupt replays the timed edges through GPIOA BSRR, and the BSRR
writes (logged by QEMU's unimplemented-device log, `-d unimp`) are checked per axis:
  * net steps (rising STEP edges counted +1 / -1 by the DIR level at that moment) equal
    steps(end) - steps(start) of the job file and machine file, computed here
    (steps(p) = round half away from zero of p x steps_per_mm, docs/step_generation.md);
  * the whole step walk (every step, in order) equals the one the captured setpoints give under
    that rounding rule, so no pulse pair was lost or added;
  * DIR changes only while that axis's STEP is low; STEP strictly alternates high, low (ending low);
  * one edge per BSRR write, only on PA0..PA5.
Only order and counts are checked, not pulse widths: QEMU 7.2's TIM2 model (stm32f2xx_timer) has
no compare interrupts and raises its update interrupt at a period unrelated to the counter, so
when an edge reaches the pins in QEMU says nothing about the firmware's schedule (docs/boards.md,
"Step edges in QEMU"). QEMU plays the edges only at those update interrupts; the board, seeing an
emulator, plays its oldest edge at once when its 256-edge ring is full (on silicon that would be
a lost edge and a StepsLost fault), so jobs of any length keep order and counts.
--steps-per-mm writes a copy of the machine file with other resolutions (a shorter run).
Exit 77 (skipped) when this curvestep has no `stream`.
Usage: step_edges_test.py <board> <firmware.elf> <curvestep> <job.json> <machine.json>
                          [--steps-per-mm X,Y,Z] [--feed MM_PER_S]"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from fractions import Fraction

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hil_stream_test import read_csv  # noqa: E402
from qemu_board import MACHINES, QemuBoard, curvestep_can_stream  # noqa: E402

AXES = "xyz"
STEP_PINS, DIR_PINS = (0, 1, 2), (3, 4, 5)  # PA0..PA2, PA3..PA5 (boards/stm32_common/.../board.hpp)
BSRR_OFFSET = {"stm32f4": 0x18, "stm32f2-m3": 0x18}
EDGE_RING = 256  # Stm32F4Chip::edge_ring
TIM2_EXCEPTION = 16 + 28  # TIM2 global interrupt
BSRR_WRITE = re.compile(r"GPIOA: unimplemented device write \(size 4, offset (0x[0-9a-f]+), value (0x[0-9a-f]+)\)")
TIM2_PENDING = re.compile(rf"nvic_set_pending NVIC set pending irq {TIM2_EXCEPTION} ")


def steps(position_mm, steps_per_mm):
    """round_half_away_from_zero(p x steps_per_mm), exactly (decimal job values as fractions)."""
    product = Fraction(position_mm) * Fraction(steps_per_mm)
    magnitude = abs(product)
    count = int(magnitude + Fraction(1, 2))  # floor(|x| + 1/2)
    return count if product >= 0 else -count


def job_end_points(job):
    """The job's first and last points (mm, 3 coordinates) from the job file alone."""
    scale = Fraction("25.4") if job.get("units", "mm") == "in" else Fraction(1)

    def point(raw):
        coordinates = [Fraction(str(value)) * scale for value in raw]
        return coordinates + [Fraction(0)] * (3 - len(coordinates))

    return point(job["segments"][0]["points"][0]), point(job["segments"][-1]["points"][-1])


def walk_of_counts(counts):
    """Unit steps (+1/-1) that take the position through counts[0], counts[1], ... in order."""
    walk = []
    for previous, current in zip(counts, counts[1:]):
        walk += [1 if current > previous else -1] * abs(current - previous)
    return walk


def turning_points(walk, start=0):
    """Positions where a walk starts, reverses and ends (a compact, comparable form of it)."""
    points, position = [start], start
    for index, step in enumerate(walk):
        position += step
        if index + 1 == len(walk) or walk[index + 1] != step:
            points.append(position)
    return points


class BsrrLog:
    """Incremental reader of the QEMU log: BSRR writes and TIM2 interrupts, in log order."""

    def __init__(self, path, offset):
        self.path, self.bsrr_offset = path, offset
        self.position, self.partial = 0, ""
        self.writes, self.tim2_interrupts, self.other_gpio_writes = [], 0, 0
        self.interrupts_at_write = []  # TIM2 interrupts seen before each BSRR write

    def poll(self):
        if not os.path.exists(self.path):
            return
        with open(self.path, encoding="utf-8", errors="replace") as handle:
            handle.seek(self.position)
            chunk = handle.read()
            self.position = handle.tell()
        lines = (self.partial + chunk).split("\n")
        self.partial = lines.pop()
        for line in lines:
            if TIM2_PENDING.search(line):
                self.tim2_interrupts += 1
                continue
            match = BSRR_WRITE.search(line)
            if not match:
                continue
            if int(match.group(1), 16) == self.bsrr_offset:
                self.writes.append(int(match.group(2), 16))
                self.interrupts_at_write.append(self.tim2_interrupts)


def check_pins(writes):
    """Replays the BSRR writes; returns (the step walk of each axis, failures)."""
    failures = []
    step_high, dir_high = [False] * 3, [False] * 3  # GPIOx_ODR resets to 0 (RM0090 §8.4.6)
    walks = [[] for _ in AXES]
    known_bits = sum(1 << pin for pin in STEP_PINS + DIR_PINS)
    for index, value in enumerate(writes):
        sets, resets = value & 0xFFFF, value >> 16
        if (sets | resets) & ~known_bits:
            failures.append(f"write {index}: 0x{value:08x} touches pins other than PA0..PA5")
        if bin(value).count("1") != 1:
            failures.append(f"write {index}: 0x{value:08x} is not exactly one edge")
        for axis, name in enumerate(AXES):
            step_bit, dir_bit = 1 << STEP_PINS[axis], 1 << DIR_PINS[axis]
            for high, bits in ((True, sets), (False, resets)):
                if bits & dir_bit and high != dir_high[axis]:
                    if step_high[axis]:
                        failures.append(f"write {index}: DIR {name} changes while STEP {name} is high")
                    dir_high[axis] = high
                if bits & step_bit:
                    if high == step_high[axis]:
                        failures.append(f"write {index}: STEP {name} set {'high' if high else 'low'} twice in a row")
                    elif high:
                        walks[axis].append(1 if dir_high[axis] else -1)
                    step_high[axis] = high
    for axis, name in enumerate(AXES):
        if step_high[axis]:
            failures.append(f"STEP {name} is still high after the last write")
    return walks, failures


def main():
    parser = argparse.ArgumentParser()
    for name in ("board", "elf", "curvestep", "job", "machine"):
        parser.add_argument(name)
    parser.add_argument("--steps-per-mm", help="X,Y,Z: stream with a copy of the machine using these")
    parser.add_argument("--feed", type=float, help="stream a copy of the job with every segment at this feed")
    parser.add_argument("--quiet-interrupts", type=int, default=6,
                        help="TIM2 interrupts without a BSRR write that end the wait after the stream (in QEMU "
                             "each moves the player 65.5 ms on: the jobs here have no such gap between edges)")
    parser.add_argument("--deadline", type=float, default=150.0, help="seconds for the whole run")
    args = parser.parse_args()
    if not curvestep_can_stream(args.curvestep):
        return 77
    started, job_name = time.monotonic(), os.path.basename(args.job)
    with open(args.job, encoding="utf-8") as handle:
        job = json.load(handle)
    with open(args.machine, encoding="utf-8") as handle:
        machine = json.load(handle)
    with tempfile.TemporaryDirectory(prefix="curvestep-edges-") as work:
        if args.steps_per_mm:
            for axis, value in zip(AXES, args.steps_per_mm.split(",")):
                machine["axes"][axis]["steps_per_mm"] = float(value)
            args.machine = os.path.join(work, "machine.json")
            with open(args.machine, "w", encoding="utf-8") as handle:
                json.dump(machine, handle)
        if args.feed:
            for segment in job["segments"]:
                segment["feed"] = args.feed
            args.job = os.path.join(work, "job.json")
            with open(args.job, "w", encoding="utf-8") as handle:
                json.dump(job, handle)
        scale = [str(machine["axes"][axis]["steps_per_mm"]) for axis in AXES]
        capture, log_path = os.path.join(work, "device.csv"), os.path.join(work, "qemu.log")
        log = BsrrLog(log_path, BSRR_OFFSET[args.board])
        with QemuBoard(MACHINES[args.board], args.elf, extra=["-trace", "nvic_set_pending"], log=log_path,
                       open_pty=False, wall_limit=args.deadline) as board:
            stream = subprocess.run([args.curvestep, "stream", args.job, "--machine", args.machine,
                                     "--port", board.pty, "--capture", capture],
                                    capture_output=True, text=True, timeout=100)
            print(stream.stdout + stream.stderr)
            if stream.returncode != 0:
                print(f"FAIL: curvestep stream exited with {stream.returncode}")
                return 1
            # QEMU plays the edges late (docs/boards.md): wait until TIM2 has interrupted
            # --quiet-interrupts times since the stream ended and since the last BSRR write.
            streamed = time.monotonic()
            log.poll()
            at_stream_end = log.tim2_interrupts
            while True:
                log.poll()
                last_write = log.interrupts_at_write[-1] if log.writes else 0
                if log.tim2_interrupts - max(last_write, at_stream_end) >= args.quiet_interrupts:
                    break
                if time.monotonic() - started > args.deadline:
                    print(f"FAIL: edges still arriving after {args.deadline} s "
                          f"({len(log.writes)} BSRR writes, {log.tim2_interrupts} TIM2 interrupts)")
                    return 1
                time.sleep(0.2)
            drained = time.monotonic()
        log.poll()
        rows = read_csv(capture)
    if not rows:
        print("FAIL: no setpoints captured")
        return 1

    # The step walk the captured setpoints ask for (Q16.16 on the wire; the float firmware rounds
    # its own float values, which differ by < 2^-17 mm: a setpoint that close to a half step could
    # round either way, so report how many there are).
    expected_walks, near_half = [], 0
    for axis, name in enumerate(AXES):
        counts = [steps(row[name], scale[axis]) for row in rows]
        near_half += sum(1 for row in rows
                         if abs(abs(Fraction(row[name]) * Fraction(scale[axis])) % 1 - Fraction(1, 2))
                         < Fraction(scale[axis]) / 2**17)
        expected_walks.append(walk_of_counts(counts))
    start, end = job_end_points(job)
    expected_net = [steps(end[axis], scale[axis]) - steps(start[axis], scale[axis]) for axis in range(3)]
    total_edges = sum(2 * len(walk) + sum(1 for a, b in zip([0] + walk, walk) if a != b) for walk in expected_walks)
    feed = f" at feed {args.feed:g}" if args.feed else ""
    print(f"job {job_name}{feed}, steps/mm {','.join(scale)}: {len(rows)} setpoints, "
          f"about {total_edges} edges expected")
    if total_edges >= EDGE_RING:
        print(f"NOTE: {total_edges} edges >= the {EDGE_RING}-edge ring: in QEMU the board plays the oldest when it is full")

    # Every BSRR write is an edge of the job: the firmware writes none before (its set-up uses
    # MODER, OSPEEDR and AFRH only).
    walks, failures = check_pins(log.writes)
    bursts = len(set(log.interrupts_at_write))
    print(f"{len(log.writes)} BSRR writes in {bursts} bursts, {log.tim2_interrupts} TIM2 interrupts; "
          f"stream took {streamed - started:.1f} s, edges drained {drained - streamed:.1f} s later")
    for axis, name in enumerate(AXES):
        walk, expected = walks[axis], expected_walks[axis]
        net = sum(walk)
        print(f"  {name}: {walk.count(1)} steps +, {walk.count(-1)} steps -, net {net} "
              f"(job file: {expected_net[axis]}); turning points {turning_points(walk)[:12]}")
        if net != expected_net[axis]:
            failures.append(f"{name}: net {net} steps, the job file gives {expected_net[axis]}")
        if walk != expected:
            failures.append(f"{name}: the step walk differs from the captured setpoints': device "
                            f"{turning_points(walk)[:20]} ({len(walk)} steps), setpoints "
                            f"{turning_points(expected)[:20]} ({len(expected)} steps); "
                            f"{near_half} setpoints within 2^-17 mm of a half step")
    if failures:
        for failure in failures[:20]:
            print("FAIL:", failure)
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
