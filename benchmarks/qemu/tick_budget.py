#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Real-time budget of the STM32 firmware images: instructions per control tick and per planned
segment on whole jobs, in QEMU 7.2, against each board's tick period and the jobs' segment rate.

Method. The images are the firmware images built with CURVESTEP_TICK_PROFILE=ON (tests/qemu/
build_image.sh ... -DCURVESTEP_TICK_PROFILE=ON): their main loop times every on_tick() and every
poll() on the board's cycle clock into `curvestep_tick_profile` (boards/stm32_common/include/
curvestep/boards/stm32/tick_profile.hpp). In QEMU the board has no DWT cycle counter and times with
SysTick's count and counter; QEMU runs with -icount shift=0, so virtual time advances exactly 1 ns
per executed instruction and SysTick counts QEMU_CLOCK_HZ[machine] per virtual second: one cycle of
the board's clock is 1e9 / QEMU_CLOCK_HZ instructions. `curvestep stream` uploads the job over
-serial pty; afterwards the profile is read from guest memory with the QEMU monitor (xp).
Figures are executed instructions (interrupts included), not cycles: on silicon a Cortex-M3/M4 at
72 / 168 MHz runs from flash with 2 / 5 wait states behind a prefetch buffer (F1) or the ART
accelerator (F4), so CPI is taken as 1.0 (best) to 1.3 (assumed for the verdict); the budget holds
if it holds at CPI 1.3.

Budget per board image and job:
  * worst tick <= 50 % of the tick period at the board's clock (72 MHz STM32F103, 168 MHz STM32F405);
  * planning throughput >= the segments per second the job needs at feed: segments (or pieces) the
    board accepted / job duration (setpoints / rate), against clock / CPI / (instructions to accept
    one + to begin one: the ticks that began a segment and the polls that accepted one).

Usage: tick_budget.py --curvestep BIN --machine machine.json [--json OUT] [--quick]
                      --image BOARD:KIND:QEMU_MACHINE:ELF ... --job JOB ...
  BOARD stm32f1 | stm32f4 (the silicon whose clock the budget uses), KIND planner | executor.
--quick: checks that each run produced a profile (for CTest); the figures are still printed."""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "qemu"))
from qemu_board import QemuBoard, read_words  # noqa: E402

# SysTick's processor clock in QEMU 7.2 (SYSCLK_FRQ of hw/arm/stm32f100_soc.c, stm32f205_soc.c, stm32f405_soc.c).
QEMU_CLOCK_HZ = {"stm32vldiscovery": 24_000_000, "netduino2": 120_000_000, "netduinoplus2": 168_000_000}
# The silicon: core clock after the boards' clock set-up (boards/stm32f1/board.cpp, boards/stm32f4/board.cpp).
BOARD_CLOCK_HZ = {"stm32f1": 72_000_000, "stm32f4": 168_000_000}
CPI_RANGE = (1.0, 1.3)  # documented assumption (module docstring); the verdict uses the upper end
TICK_BUDGET_SHARE = 0.5
PROFILE_WORDS = 16 + 128  # tick_profile.hpp


# The figures every result must carry (--quick checks they are there, not their values).
REQUIRED_FIGURES = ("instructions_per_tick.worst", "instructions_per_tick.mean", "instructions_per_tick.p99_at_most",
                    "instructions_per_segment.total_mean", "budget.worst_tick_share_of_period",
                    "budget.segments_per_s_needed", "budget.segments_per_s_possible", "within_budget")


def has_figure(result, path):
    value = result
    for key in path.split("."):
        if not isinstance(value, dict) or key not in value:
            return False
        value = value[key]
    return value is not None


def symbol_address(elf, name):
    for line in subprocess.run(["arm-none-eabi-nm", elf], capture_output=True, text=True, check=True).stdout.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[2] == name:
            return int(parts[0], 16)
    raise SystemExit(f"{elf}: no {name} (build it with -DCURVESTEP_TICK_PROFILE=ON)")


def decode_profile(words):
    if words[0] != 0x6B636974:
        raise RuntimeError(f"no tick profile at the symbol (magic {words[0]:#x})")
    pair = lambda k: words[k] | (words[k + 1] << 32)  # noqa: E731
    return {"tick_cycles_sum": pair(2), "start_cycles_sum": pair(4), "accept_cycles_sum": pair(6),
            "ticks": words[8], "tick_cycles_max": words[9], "starts": words[10], "start_cycles_max": words[11],
            "accepted": words[12], "accept_cycles_max": words[13], "cycles_per_second": words[14],
            "overruns": words[15], "histogram": words[16:16 + 128]}


def bucket_upper(index):
    """Upper end (exclusive) of a histogram bucket (tick_profile.hpp)."""
    if index < 4:
        return index + 1
    octave, sub = divmod(index, 4)
    return (1 << octave) * (1 + (sub + 1) / 4)


def percentile_cycles(histogram, fraction, maximum):
    total = sum(histogram)
    if total == 0:
        return 0
    target, running = math.ceil(fraction * total), 0
    for index, count in enumerate(histogram):
        running += count
        if running >= target:
            return min(bucket_upper(index), maximum)
    return maximum


def run_job(image, job, args, work):
    board, kind, machine, elf = image
    address = symbol_address(elf, "curvestep_tick_profile")
    monitor = os.path.join(work, f"monitor-{os.getpid()}.sock")
    capture = os.path.join(work, "capture.csv")
    extra = ["-icount", "shift=0", "-monitor", f"unix:{monitor},server,nowait"]
    with QemuBoard(machine, elf, extra=extra, open_pty=False, wall_limit=args.wall_limit) as qemu:
        command = [args.curvestep, "stream", job, "--machine", args.machine, "--port", qemu.pty, "--capture", capture,
                   "--link-timeout-ms", "30000"]  # QEMU's -icount pace is not the link's concern here
        stream = subprocess.run(command, capture_output=True, text=True, timeout=args.wall_limit)
        if stream.returncode != 0:
            return {"error": f"curvestep stream exited with {stream.returncode}: {(stream.stdout + stream.stderr)[-400:]}"}
        profile = decode_profile(read_words(monitor, address, PROFILE_WORDS))
    with open(capture, encoding="utf-8") as handle:
        setpoints = max(0, sum(1 for _ in handle) - 1)
    with open(args.machine, encoding="utf-8") as handle:
        rate_hz = json.load(handle)["rate_hz"]
    return figures(board, machine, profile, setpoints, rate_hz)


def figures(board, machine, p, setpoints, rate_hz):
    instructions = 1e9 / QEMU_CLOCK_HZ[machine]  # per cycle of the board's clock in QEMU
    clock = BOARD_CLOCK_HZ[board]
    period_cycles = clock / rate_hz
    ticks = max(p["ticks"], 1)
    worst = p["tick_cycles_max"] * instructions
    mean = p["tick_cycles_sum"] / ticks * instructions
    p99 = percentile_cycles(p["histogram"], 0.99, p["tick_cycles_max"]) * instructions
    begin = p["start_cycles_sum"] / max(p["starts"], 1) * instructions
    accept = p["accept_cycles_sum"] / max(p["accepted"], 1) * instructions
    per_segment = begin + accept
    duration_s = setpoints / rate_hz
    needed = p["accepted"] / duration_s if duration_s > 0 else 0.0
    cpi = CPI_RANGE[1]
    tick_share = mean * cpi / period_cycles  # the CPU the ticks take on average
    capacity = clock / cpi * max(0.0, 1.0 - tick_share) / per_segment if per_segment > 0 else float("inf")
    worst_share = worst * cpi / period_cycles
    return {
        "ticks": p["ticks"], "setpoints": setpoints, "job_duration_s": round(duration_s, 3),
        "instructions_per_tick": {"worst": round(worst), "mean": round(mean, 1), "p99_at_most": round(p99)},
        "segments": p["accepted"], "segment_starts": p["starts"],
        "instructions_per_segment": {"begin_in_tick_mean": round(begin), "begin_in_tick_worst": round(p["start_cycles_max"] * instructions),
                                     "accept_in_poll_mean": round(accept), "total_mean": round(per_segment)},
        "overruns_counted_in_qemu": p["overruns"],
        "budget": {
            "clock_hz": clock, "rate_hz": rate_hz, "period_instructions_at_cpi_1": round(period_cycles),
            "cpi_assumed": list(CPI_RANGE),
            "worst_tick_share_of_period": [round(worst * c / period_cycles, 4) for c in CPI_RANGE],
            "worst_tick_within_50_percent": worst_share <= TICK_BUDGET_SHARE,
            "segments_per_s_needed": round(needed, 1),
            "segments_per_s_possible": round(capacity, 1) if math.isfinite(capacity) else None,
            "planning_throughput_sufficient": capacity >= needed,
        },
        "within_budget": worst_share <= TICK_BUDGET_SHARE and capacity >= needed,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--curvestep", required=True)
    parser.add_argument("--machine", required=True)
    parser.add_argument("--image", action="append", required=True, help="BOARD:KIND:QEMU_MACHINE:ELF")
    parser.add_argument("--job", action="append", required=True)
    parser.add_argument("--json")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--wall-limit", type=float, default=600.0)
    args = parser.parse_args()
    images = []
    for spec in args.image:
        board, kind, machine, elf = spec.split(":", 3)
        if board not in BOARD_CLOCK_HZ or machine not in QEMU_CLOCK_HZ or kind not in ("planner", "executor"):
            raise SystemExit(f"bad --image {spec}")
        images.append((board, kind, machine, elf))
    results = []
    with tempfile.TemporaryDirectory(prefix=f"curvestep-tick-{os.getpid()}-") as work:
        for image in images:
            for job in args.job:
                entry = {"board": image[0], "image": image[1], "qemu_machine": image[2], "elf": os.path.basename(image[3]),
                         "job": os.path.basename(job)}
                try:
                    entry.update(run_job(image, job, args, work))
                except (RuntimeError, TimeoutError, subprocess.TimeoutExpired) as error:
                    entry["error"] = str(error)
                results.append(entry)
                print(json.dumps(entry), file=sys.stderr, flush=True)
    report = {"method": "QEMU 7.2 -icount shift=0 (1 ns per instruction); SysTick-timed ticks and polls in the "
                        "firmware (CURVESTEP_TICK_PROFILE); instructions, not cycles",
              "cpi_assumption": {"range": list(CPI_RANGE), "verdict_at": CPI_RANGE[1],
                                 "why": "Cortex-M3/M4 from flash with wait states (F1: 2, prefetch; F4: 5, ART accelerator)"},
              "tick_budget_share": TICK_BUDGET_SHARE, "machine": os.path.basename(args.machine), "results": results}
    text = json.dumps(report, indent=2)
    print(text)
    if args.json:
        with open(args.json, "w", encoding="utf-8") as handle:
            handle.write(text + "\n")
    if args.quick:
        missing = [f"{r['board']} {r['image']} {r['job']}: {path}" for r in results for path in REQUIRED_FIGURES
                   if not has_figure(r, path)]
        if missing:
            print("FAIL: figures missing: " + "; ".join(missing), file=sys.stderr)
            return 1
        json.loads(text)  # well formed
    failed = [r for r in results if "error" in r or r.get("ticks", 0) == 0]
    if failed:
        print(f"FAIL: {len(failed)} run(s) without a profile: " + "; ".join(r.get("error", "no ticks") for r in failed), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
