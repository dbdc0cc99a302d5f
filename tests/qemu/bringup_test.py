#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""QEMU bring-up tests of the STM32 images (one scenario per CTest test).
Usage: bringup_test.py <stm32f1|stm32f4> <image.elf> <hello|echo|tick|gpio|fault>"""
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from qemu_board import MACHINES, QemuBoard  # noqa: E402

# GPIOA BSRR offset from the reference manuals: RM0008 §9.2.5 (F1), RM0090 §8.4.7 (F4).
BSRR_OFFSET = {"stm32f1": 0x10, "stm32f4": 0x18}
STEP_PINS, DIR_PINS = (0, 1, 2), (3, 4, 5)  # PA0-PA2, PA3-PA5 (boards/*/README.md)


def check(condition, message):
    if not condition:
        print("FAIL:", message)
        sys.exit(1)


def main():
    board_name, elf, scenario = sys.argv[1], sys.argv[2], sys.argv[3]
    log = tempfile.NamedTemporaryFile(prefix="qemu-unimp-", suffix=".log", delete=False).name
    try:
        with QemuBoard(MACHINES[board_name], elf, log=log if scenario == "gpio" else None) as board:
            hello = board.handshake()
            check(board_name.encode() in hello.group(0), f"wrong board answered: {hello.group(0)!r}")
            if scenario == "hello":
                print("answer:", hello.group(0).decode().strip())
            elif scenario == "echo":
                lines = [f"echo line {i:02d} " + "abcdefghijklmnopqrstuvwxyz0123456789" for i in range(12)]
                board.send("".join(line + "\n" for line in lines))  # 12 x 50 bytes, more than the 256-byte ring
                for line in lines:
                    board.expect(re.escape(line[5:].encode()) + rb"\r\n")
                board.send("stats\n")
                stats = board.expect(rb"stats overruns=(\d+) ticks=(\d+)\r\n")
                check(stats.group(1) == b"0", f"receive overruns: {stats.group(0)!r}")
                board.send("bogus\n")
                board.expect(rb"error: unknown command\r\n")
            elif scenario == "tick":
                board.send("tick\n")
                tick = board.expect(rb"tick ok (\d+) (\d+)\r\n")
                first, last = int(tick.group(1)), int(tick.group(2))
                check(last - first >= 20, f"tick advanced only {last - first}")
                board.send("tick\n")
                again = board.expect(rb"tick ok (\d+) (\d+)\r\n")
                check(int(again.group(1)) >= last, "tick count went backwards")
            elif scenario == "gpio":
                board.send("gpio\n")
                board.expect(rb"gpio ok\r\n")
            elif scenario == "fault":
                board.send("fault\n")
                report = board.expect(rb"HardFault pc=0x([0-9a-f]{8}) lr=0x[0-9a-f]{8} xpsr=0x[0-9a-f]{8} "
                                      rb"cfsr=0x([0-9a-f]{8}) hfsr=0x([0-9a-f]{8}) mmfar=0x[0-9a-f]{8} bfar=0x[0-9a-f]{8}\r\n")
                pc, cfsr, hfsr = (int(report.group(i), 16) for i in (1, 2, 3))
                check(cfsr == 1 << 16, f"CFSR should be UNDEFINSTR (bit 16), is {cfsr:#x}")
                check(hfsr == 1 << 30, f"HFSR should be FORCED (bit 30), is {hfsr:#x}")
                # The stacked PC must be the image's one udf instruction (found independently by objdump).
                listing = subprocess.run(["arm-none-eabi-objdump", "-d", elf], capture_output=True, text=True,
                                         check=True).stdout
                udf = [int(m.group(1), 16) for m in re.finditer(r"^\s*([0-9a-f]+):\s+[0-9a-f ]+\s+udf", listing, re.M)]
                check(pc in udf, f"fault pc {pc:#x} is not the udf instruction {[hex(u) for u in udf]}")
                print(f"report: pc={pc:#x} cfsr={cfsr:#x} hfsr={hfsr:#x}")
            else:
                check(False, f"unknown scenario {scenario}")
        if scenario == "gpio":
            with open(log, encoding="utf-8", errors="replace") as handle:
                writes = [int(m.group(1), 16) for m in re.finditer(
                    rf"GPIOA: unimplemented device write \(size 4, offset {BSRR_OFFSET[board_name]:#05x}, value (0x[0-9a-f]+)\)",
                    handle.read())]
            dirs = (1 << DIR_PINS[0]) | (1 << DIR_PINS[2]) | (1 << (DIR_PINS[1] + 16))  # X, Z positive; Y negative
            steps = sum(1 << pin for pin in STEP_PINS)
            expected = [dirs, steps, steps << 16]
            check(writes[-3:] == expected,
                  f"BSRR writes {[hex(w) for w in writes]} do not end with {[hex(e) for e in expected]}")
            print("BSRR writes:", [hex(w) for w in writes])
    finally:
        os.unlink(log)
    print("PASS")


if __name__ == "__main__":
    main()
