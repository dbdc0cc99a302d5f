#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Machine outputs of the STM32 firmware in QEMU (docs/boards.md, "Machine outputs"): real jobs
with machine events are streamed by `curvestep stream` to the App<Board> firmware over -serial pty,
and what the board's hooks wrote is read back:
  * TIM4 (servo pen, PB6) and TIM3 (spindle PWM, PA6) through the QEMU monitor (`xp` on the
    timer registers, which QEMU 7.2's stm32f2xx_timer models): the prescaler, the period and the
    compare value, polled while the job runs (each pen or spindle state lasts at least a second:
    the pen's settle dwell, G4 P1), so the sequence of compare values is the sequence of events;
  * the output pins on GPIOB (not modelled: every BSRR write is in the -d unimp log), in order.
Expected values are computed here from the reference manual and the pin table, not taken from
the firmware: QEMU's netduinoplus2 gives the board no RCC, so it runs on the emulator's clocks
(HCLK 168 MHz, PCLK1 42 MHz with the APB1 prescaler 4: the APB1 timers run at 2 x 42 = 84 MHz,
RM0090 §6.2) and both timers count microseconds with PSC = 84 - 1; the servo's period is
(ARR + 1) x (PSC + 1) / 84 MHz = 20 ms for ARR = 19999, its pulse widths are the machine file's
up_pulse_us / down_pulse_us, and the spindle's duty is rpm / 24000 (the default
CURVESTEP_SPINDLE_MAX_RPM) of a 1000-count period.
The Cortex-M3 build of the board code (stm32f2-m3 on netduino2, the F1 firmware's Q16.16 App) is
checked with --timers-only: QEMU's STM32F205 logs no GPIO writes.
Exit 77 (skipped) when this curvestep has no `stream`.
Usage: machine_outputs_test.py <board> <firmware.elf> <curvestep> <machine.json> [--timers-only]"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from qemu_board import MACHINES, QemuBoard, QemuMonitor, curvestep_can_stream  # noqa: E402

TIM3, TIM4 = 0x40000400, 0x40000800  # RM0090 Table 1 (the same addresses on the F1: RM0008 Table 3)
CR1, CCMR1, CCER, PSC, ARR, CCR1 = 0x00, 0x18, 0x20, 0x28, 0x2C, 0x34  # RM0090 §18.4
TIMER_CLOCK_HZ = 2 * 42_000_000  # APB1 timers: twice PCLK1 when the APB1 prescaler is not 1
GPIOB_BSRR = re.compile(r"GPIOB: unimplemented device write \(size 4, offset 0x0*18, value (0x[0-9a-f]+)\)")
UP_US, DOWN_US = 1250, 1800  # the servo pen of this test's machine file
MAX_RPM = 24000
SPINDLE_PERIOD = 1000  # counts of the spindle PWM (1 kHz at 1 MHz)

DRAWING = """<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="40mm" viewBox="0 0 40 40">
  <path d="M 5 5 L 15 5" stroke="black" fill="none"/>
  <path d="M 25 25 L 35 25" stroke="black" fill="none"/>
</svg>
"""

# Each state held for at least a second (G4 P1) so that polling sees it.
PROGRAM = """G21 G90 G94
G0 X0 Y0
M3 S6000
G4 P1
M8
G1 X5 F600
S10001
G4 P1
M62 P2
G1 X10
M4 S3000
G4 P1
M7
M9
M65 P2
M5
G4 P1
G1 X12
M30
"""


def bit(pin, high):
    """The GPIOx_BSRR bit that drives `pin` high (BSx) or low (BRx) (RM0090 §8.4.7)."""
    return 1 << pin if high else 1 << (pin + 16)


EN, CCW, MIST, FLOOD, OUT0 = 12, 13, 14, 15, 8  # PB12..PB15, PB8 + n (docs/boards.md pin table)
EXPECTED_GPIOB = [
    # board start: every output low
    sum(bit(pin, False) for pin in (EN, CCW, MIST, FLOOD, OUT0, OUT0 + 1, OUT0 + 2, OUT0 + 3)),
    bit(EN, True) | bit(CCW, False),   # M3 S6000: on, clockwise
    bit(MIST, False) | bit(FLOOD, True),  # M8
    bit(EN, True) | bit(CCW, False),   # S10001: the spindle's whole state again
    bit(OUT0 + 2, True),               # M62 P2
    bit(EN, True) | bit(CCW, True),    # M4 S3000: counter-clockwise
    bit(MIST, True) | bit(FLOOD, True),   # M7: mist with the flood
    bit(MIST, False) | bit(FLOOD, False),  # M9
    bit(OUT0 + 2, False),              # M65 P2
    bit(EN, False) | bit(CCW, True),   # M5: off (the direction pin keeps M4's level)
]
EXPECTED_SPINDLE_DUTY = [0] + [round(SPINDLE_PERIOD * rpm / MAX_RPM) for rpm in (6000, 10001, 3000)] + [0]  # 250, 417, 125
EXPECTED_PEN = [0, UP_US, DOWN_US, UP_US, DOWN_US, UP_US]  # no pulse, then lifted once, two strokes


def distinct(values):
    out = []
    for value in values:
        if not out or out[-1] != value:
            out.append(value)
    return out


def stream_and_poll(curvestep, job, machine, board, monitor, timer, deadline):
    """Streams `job` and polls `timer`'s CCR1 every 20 ms while it runs; returns the distinct values."""
    command = [curvestep, "stream", job, "--machine", machine, "--port", board.pty]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    seen = [monitor.words(timer + CCR1, 1)[0]]
    while process.poll() is None:
        if time.monotonic() > deadline:
            process.kill()
            raise TimeoutError(f"{job}: the stream did not end in time")
        seen.append(monitor.words(timer + CCR1, 1)[0])
        time.sleep(0.02)
    output = process.stdout.read()
    print(output)
    seen.append(monitor.words(timer + CCR1, 1)[0])
    if process.returncode != 0:
        raise RuntimeError(f"curvestep stream {os.path.basename(job)} exited with {process.returncode}")
    return distinct(seen)


def check_timer(name, registers, period, failures):
    cr1, ccmr1, ccer, psc, arr = (registers[k] for k in ("cr1", "ccmr1", "ccer", "psc", "arr"))
    print(f"{name}: CR1 {cr1:#x} CCMR1 {ccmr1:#x} CCER {ccer:#x} PSC {psc} ARR {arr} CCR1 {registers['ccr1']}; "
          f"period {(arr + 1) * (psc + 1) / TIMER_CLOCK_HZ * 1000:g} ms")
    if psc != TIMER_CLOCK_HZ // 1_000_000 - 1:
        failures.append(f"{name}: PSC {psc}, expected {TIMER_CLOCK_HZ // 1_000_000 - 1} (1 MHz from 84 MHz)")
    if (arr + 1) * (psc + 1) != period * TIMER_CLOCK_HZ // 1_000_000:
        failures.append(f"{name}: period {(arr + 1) * (psc + 1)} timer clocks, expected {period} us")
    if ccmr1 & 0xFF != 0x68:  # OC1M = 110 (PWM mode 1), OC1PE (preload), CC1S = 00 (output)
        failures.append(f"{name}: CCMR1 {ccmr1:#x}, expected channel 1 in PWM mode 1 with preload (0x68)")
    if ccer & 0x3 != 0x1:  # CC1E, active high
        failures.append(f"{name}: CCER {ccer:#x}, expected CC1E active high")
    if cr1 & 0x81 != 0x81:  # CEN, ARPE
        failures.append(f"{name}: CR1 {cr1:#x}, expected counting with ARR preload")


def timer_registers(monitor, timer):
    words = monitor.words(timer, (CCR1 >> 2) + 1)
    return {"cr1": words[CR1 >> 2], "ccmr1": words[CCMR1 >> 2], "ccer": words[CCER >> 2], "psc": words[PSC >> 2],
            "arr": words[ARR >> 2], "ccr1": words[CCR1 >> 2]}


def main():
    parser = argparse.ArgumentParser()
    for name in ("board", "elf", "curvestep", "machine"):
        parser.add_argument(name)
    parser.add_argument("--deadline", type=float, default=150.0, help="seconds for the whole run")
    parser.add_argument("--timers-only", action="store_true",
                        help="check the timers only: the machine logs no GPIO writes (netduino2's STM32F205 has no "
                             "unimplemented-device GPIO ports)")
    args = parser.parse_args()
    if not curvestep_can_stream(args.curvestep):
        return 77
    deadline = time.monotonic() + args.deadline
    failures = []
    with open(args.machine, encoding="utf-8") as handle:
        machine = json.load(handle)
    with tempfile.TemporaryDirectory(prefix=f"curvestep-outputs-{os.getpid()}-") as work:
        pen_machine = dict(machine, pen={"axis": "servo", "line": "PB6", "up_pulse_us": UP_US, "down_pulse_us": DOWN_US,
                                         "settle": 1.0})
        paths = {name: os.path.join(work, name) for name in ("pen_machine.json", "drawing.svg", "program.ngc", "qemu.log",
                                                            "monitor.sock")}
        with open(paths["pen_machine.json"], "w", encoding="utf-8") as handle:
            json.dump(pen_machine, handle)
        with open(paths["drawing.svg"], "w", encoding="utf-8") as handle:
            handle.write(DRAWING)
        with open(paths["program.ngc"], "w", encoding="utf-8") as handle:
            handle.write(PROGRAM)
        extra = ["-monitor", f"unix:{paths['monitor.sock']},server,nowait"]
        with QemuBoard(MACHINES[args.board], args.elf, extra=extra, log=paths["qemu.log"], open_pty=False,
                       wall_limit=args.deadline) as board, QemuMonitor(paths["monitor.sock"]) as monitor:
            pen = stream_and_poll(args.curvestep, paths["drawing.svg"], paths["pen_machine.json"], board, monitor, TIM4,
                                  deadline)
            servo = timer_registers(monitor, TIM4)
            spindle_duty = stream_and_poll(args.curvestep, paths["program.ngc"], args.machine, board, monitor, TIM3,
                                           deadline)
            spindle = timer_registers(monitor, TIM3)
        with open(paths["qemu.log"], encoding="utf-8", errors="replace") as handle:
            gpiob = [int(m.group(1), 16) for m in GPIOB_BSRR.finditer(handle.read())]

    check_timer("TIM4 (servo pen)", servo, 20_000, failures)
    print(f"TIM4 CCR1 while the drawing ran: {pen} (expected {EXPECTED_PEN})")
    if pen != EXPECTED_PEN:
        failures.append(f"servo pulse widths {pen}, expected {EXPECTED_PEN}")
    check_timer("TIM3 (spindle PWM)", spindle, SPINDLE_PERIOD, failures)
    print(f"TIM3 CCR1 while the program ran: {spindle_duty} (expected {EXPECTED_SPINDLE_DUTY})")
    if spindle_duty != EXPECTED_SPINDLE_DUTY:
        failures.append(f"spindle duty counts {spindle_duty}, expected {EXPECTED_SPINDLE_DUTY}")
    print("GPIOB BSRR writes: " + " ".join(f"{value:#010x}" for value in gpiob))
    if args.timers_only:
        print("NOTE: GPIOB not checked (--timers-only)")
    elif gpiob != EXPECTED_GPIOB:
        failures.append("GPIOB BSRR writes differ: expected " + " ".join(f"{value:#010x}" for value in EXPECTED_GPIOB))
    if failures:
        for failure in failures:
            print("FAIL: " + failure)
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
