#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The App<Board> firmware image in QEMU answers the protocol handshake over -serial pty:
Hello(version 5, session 0x1234) -> Capabilities (docs/protocol.md). The frame bytes are built
here independently of the C++ encoder (COBS, the payload's CRC-32C table-driven, the frame's
CRC-16/CCITT-FALSE via binascii.crc_hqx).
Usage: firmware_test.py <stm32f1|stm32f4|stm32f2-m3> <firmware.elf> [--executor]
--executor: the image without a planner (look-ahead 0, no Bézier degree: it takes host-planned
pieces, not segments), which runs on the F1's own QEMU machine (8 KiB of RAM)."""
import binascii
import os
import struct
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from qemu_board import MACHINES, QemuBoard  # noqa: E402

# Queue slots and look-ahead of each board's firmware image (boards/<board>/CMakeLists.txt, firmware_main.cpp).
EXPECTED_QUEUE_AND_LOOKAHEAD = {"stm32f1": (16, 8), "stm32f4": (32, 16), "stm32f2-m3": (16, 8)}
# The STM32F1 executor image (boards/stm32f1/CMakeLists.txt): 16 pieces, no planner.
EXECUTOR_QUEUE_AND_LOOKAHEAD = (16, 0)


def cobs_encode(data):
    out, block = bytearray(), bytearray()
    for byte in data:
        if byte == 0:
            out += bytes([len(block) + 1]) + block
            block = bytearray()
        else:
            block.append(byte)
            if len(block) == 254:
                out += bytes([255]) + block
                block = bytearray()
    out += bytes([len(block) + 1]) + block
    return bytes(out) + b"\x00"


def cobs_decode(data):
    out, i = bytearray(), 0
    while i < len(data):
        code = data[i]
        if code == 0 or i + code > len(data) + 0:
            raise ValueError("bad COBS")
        out += data[i + 1:i + code]
        i += code
        if code != 255 and i < len(data):
            out.append(0)
    return bytes(out)


def crc32c(data):
    """CRC-32C (Castagnoli): reflected polynomial 0x82F63B78, init and final XOR 0xFFFFFFFF."""
    table = []
    for n in range(256):
        c = n
        for _ in range(8):
            c = (c >> 1) ^ 0x82F63B78 if c & 1 else c >> 1
        table.append(c)
    crc = 0xFFFFFFFF
    for byte in data:
        crc = table[(crc ^ byte) & 0xFF] ^ (crc >> 8)
    return crc ^ 0xFFFFFFFF


def frame(message_type, sequence, message):
    body = bytes([message_type, sequence]) + message
    body += struct.pack("<I", crc32c(body))  # every payload ends with its CRC-32C (since protocol version 2)
    return cobs_encode(body + struct.pack("<H", binascii.crc_hqx(body, 0xFFFF)))


def main():
    board_name, elf = sys.argv[1], sys.argv[2]
    executor = "--executor" in sys.argv[3:]
    expected = EXECUTOR_QUEUE_AND_LOOKAHEAD if executor else EXPECTED_QUEUE_AND_LOOKAHEAD[board_name]
    expected_degree = 0 if executor else 7
    hello = frame(0x01, 0, struct.pack("<HH", 5, 0x1234))
    assert hello == bytes.fromhex("02010205093412 1f48dce1 366900".replace(" ", "")), hello.hex()  # docs/protocol.md
    with QemuBoard(MACHINES[board_name], elf) as board:
        deadline = time.monotonic() + 20
        while True:
            board.send(hello)  # QEMU drops output until it sees the pty open: repeat, as a host does
            try:
                match = board.expect(rb"([^\x00]+)\x00", timeout=0.5)
            except TimeoutError:
                if time.monotonic() > deadline:
                    raise
                continue
            decoded = cobs_decode(match.group(1))
            body, crc = decoded[:-2], struct.unpack("<H", decoded[-2:])[0]
            if crc != binascii.crc_hqx(body, 0xFFFF) or struct.unpack("<I", body[-4:])[0] != crc32c(body[:-4]):
                print("FAIL: CRC mismatch in", decoded.hex())
                return 1
            if body[0] != 0x02:
                continue  # e.g. an Ack: wait for the Capabilities
            if len(body) != 2 + 20 + 4:
                print(f"FAIL: Capabilities of {len(body) - 6} bytes (version 5: 20)")
                return 1
            (version, session, max_payload, queue, credit_end, total_bits, fraction_bits, axes, degree,
             tick_rate, lookahead) = struct.unpack("<HHHHHBBBBIH", body[2:22])
            print(f"Capabilities: version={version} session={session:#x} max_payload={max_payload} queue={queue} "
                  f"credit_end={credit_end} fixed={total_bits}/{fraction_bits} axes={axes} degree={degree} "
                  f"tick_rate={tick_rate} lookahead={lookahead}")
            # The image's queue and look-ahead (firmware_main.cpp): App needs queue >= look-ahead + 8.
            ok = (version == 5 and session == 0x1234 and max_payload == 162 and total_bits == 32 and
                  fraction_bits == 16 and axes == 3 and tick_rate == 1_000_000 and degree == expected_degree and
                  (queue, lookahead) == expected)
            print("PASS" if ok else "FAIL: unexpected Capabilities")
            return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
