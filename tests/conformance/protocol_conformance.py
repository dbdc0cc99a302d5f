#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Protocol conformance (issues 21.3 and 24): a host written from docs/protocol.md and docs/errors.md
alone, with the Python standard library, run against the real `curvestep device` on a pseudo-terminal.

It frames, sends and checks the documented examples and rules: the byte examples of the document,
the handshake, the state table's answers in the states a job passes through (NotConnected before a
Hello, a Hello of the wrong length, ConfigurationMissing, NothingQueued, UnknownMessage, BadPayload
with its byte offset, a damaged frame, a duplicate), the credit formula, and a job that runs: its
setpoints arrive in SetpointBatches, in order, and end at the segment's end point. A second device
(with a short retransmission timeout) meets a host that talks but never acknowledges setpoints:
RetransmitLimit, then every new job of that session refused with the reason, until a new Hello.

Nothing here reads the C++ sources: error numbers come from docs/errors.md's table, layouts from the
document's message tables.

    protocol_conformance.py CURVESTEP_PROGRAM DOCS_DIR
"""
import math
import os
import re
import select
import struct
import subprocess
import sys
import time
import tty

# ---- the document's encodings (docs/protocol.md, "Conventions", "Frames") ----


def crc16(data):
    """CRC-16/CCITT-FALSE: poly 0x1021, init 0xFFFF, no reflection, no final XOR."""
    crc = 0xFFFF
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) & 0xFFFF if crc & 0x8000 else (crc << 1) & 0xFFFF
    return crc


def crc32c(data):
    """CRC-32C (Castagnoli), reflected poly 0x82F63B78, init and final XOR 0xFFFFFFFF."""
    crc = 0xFFFFFFFF
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = (crc >> 1) ^ 0x82F63B78 if crc & 1 else crc >> 1
    return crc ^ 0xFFFFFFFF


def cobs_encode(data):
    out, block = bytearray(), bytearray()
    for b in data:
        if b == 0:
            out.append(len(block) + 1)
            out += block
            block = bytearray()
        else:
            block.append(b)
            if len(block) == 254:
                out.append(255)
                out += block
                block = bytearray()
    out.append(len(block) + 1)
    out += block
    return bytes(out)


def cobs_decode(block):
    out, i = bytearray(), 0
    while i < len(block):
        code = block[i]
        if code == 0 or i + code > len(block):
            return None
        out += block[i + 1:i + code]
        i += code
        if code != 255 and i < len(block):
            out.append(0)
    return bytes(out)


def frame(type_, sequence, message):
    raw = bytes([type_, sequence]) + message
    raw += struct.pack('<I', crc32c(raw))
    raw += struct.pack('<H', crc16(raw))
    return cobs_encode(raw) + b'\x00'


def parse_frame(decoded):
    """(type, sequence, message) of a decoded frame, or None if a check fails."""
    if decoded is None or len(decoded) < 8:
        return None
    if struct.unpack('<H', decoded[-2:])[0] != crc16(decoded[:-2]):
        return None
    if struct.unpack('<I', decoded[-6:-2])[0] != crc32c(decoded[:-6]):
        return None
    return decoded[0], decoded[1], decoded[2:-6]


def q16(mm):
    """Q16.16 raw: nearest, ties away from zero."""
    scaled = mm * 65536
    whole = math.floor(abs(scaled))
    whole += 1 if abs(scaled) - whole >= 0.5 else 0
    return int(math.copysign(whole, scaled))


HELLO, CAPABILITIES, ACK, NAK = 0x01, 0x02, 0x03, 0x04
CONFIGURATION, SEGMENT, START, FEED_HOLD, RESUME, ABORT, STATUS_REQUEST = 0x10, 0x11, 0x12, 0x13, 0x14, 0x15, 0x16
FEED_OVERRIDE = 0x19
STATUS_REPORT, SETPOINT_BATCH, ERROR_REPORT = 0x20, 0x21, 0x22
VERSION = 5


def configuration_message(axes=3, flags=0, v=200.0, a=2000.0, j=50000.0, tolerance=0.01, junction=0.05,
                          step_rate=100000.0, feed=50.0, rapid=0.0, rate=1000, steps=80.0):
    m = struct.pack('<BBdddddd', axes, flags, v, a, j, tolerance, junction, step_rate)
    m += struct.pack('<iiI', q16(feed), q16(rapid), rate)
    for _ in range(axes):
        m += struct.pack('<dddii', steps, v, a, 0, 0)
    return m


def line_message(start, end, feed=None, end_of_job=False):
    flags = 0x04 | (0x02 if feed is not None else 0) | (0x10 if end_of_job else 0)
    m = bytes([0, flags])
    if feed is not None:
        m += struct.pack('<i', q16(feed))
    for p in (start, end):
        m += struct.pack('<iii', *(q16(c) for c in p))
    return m


def unzigzag(n):
    return (n >> 1) ^ -(n & 1)


def decode_setpoints(message):
    first_index, axes, count = struct.unpack('<IBB', message[:6])
    position = list(struct.unpack('<' + 'i' * axes, message[6:6 + 4 * axes]))
    points, i = [tuple(position)], 6 + 4 * axes
    for _ in range(count - 1):
        for axis in range(axes):
            value, shift = 0, 0
            while True:
                b = message[i]
                i += 1
                value |= (b & 0x7F) << shift
                shift += 7
                if not b & 0x80:
                    break
            position[axis] += unzigzag(value)
        points.append(tuple(position))
    return first_index, points


# ---- checks ----

failures = []


def check(condition, what):
    print(('PASS ' if condition else 'FAIL ') + what)
    if not condition:
        failures.append(what)
    return condition


def error_codes(docs_dir):
    """Error numbers by name, from docs/errors.md's table ("| 78 | `NothingQueued` | ... |")."""
    codes = {}
    with open(os.path.join(docs_dir, 'errors.md'), encoding='utf-8') as f:
        for line in f:
            m = re.match(r'\| (\d+) \| `(\w+)` \|', line)
            if m:
                codes[m.group(2)] = int(m.group(1))
    return codes


def document_examples():
    """The byte examples the document prints, reproduced by this client's encoders."""
    check(crc16(b'123456789') == 0x29B1, 'CRC-16 check value 0x29B1')
    check(crc32c(b'123456789') == 0xE3069283, 'CRC-32C check value 0xE3069283')
    worked = frame(SEGMENT, 5, bytes([0, 2]) + struct.pack('<iiiii', q16(20), 0, 0, q16(10.5), q16(-2.25)))
    check(worked.hex(' ') == '03 11 05 02 02 01 02 14 01 01 01 01 01 01 01 01 01 03 80 0a 01 0a c0 fd ff 7a bb 32 e6 79 04 00',
          'worked example: the 2-axis line with sequence 5 on the wire')
    check(frame(HELLO, 0, struct.pack('<HH', 4, 0x1234)).hex(' ') == '02 01 02 04 09 34 12 a7 e2 99 3c 43 c8 00',
          'worked example: Hello(4, 0x1234)')
    check(frame(ACK, 7, bytes([6]) + struct.pack('<H', 40)).hex(' ') == '05 03 07 06 28 07 a6 a8 6f 27 02 fd 00',
          'worked example: Ack(6, 40) with sequence 7')
    check(q16(2.5 / 65536) == 3 and q16(-2.5 / 65536) == -3, 'q16 rounds ties away from zero')
    example = bytes.fromhex('0201' '0000000000006940' '0000000000409f40' '00000000006ae840' '7b14ae47e17a843f'
                            '9a9999999999a93f' '00000000006af840' '00003200' '00000000' 'e8030000'
                            + ('0000000000005440' '0000000000006940' '0000000000409f40' '00009cff' '00006400') * 2)
    mine = configuration_message(axes=2, flags=1, junction=0.05)
    mine = mine[:62] + b''.join(struct.pack('<dddii', 80.0, 200.0, 2000.0, q16(-100), q16(100)) for _ in range(2))
    check(len(example) == 126 and mine == example, 'MachineConfiguration example (126 bytes)')
    arc = bytes.fromhex('0134' '02000000' '00000a00' '00000000' '00000000' '00000a00' '00000000' '0000ffff' '00000000' '00000000')
    check(len(arc) == 38 and arc[1] == 0x04 | 0x10 | 0x20, 'QueueSegment arc example: flags three axes, end of job, turns')
    status = bytes.fromhex('01 00 03 11 00 20 00 40 e2 01 00 06 03 00 00 00 64 02 00 00 64 00 64 00 00 00 00 00'
                           ' 00 00 01 00 00 00 02 00 00 80 ff ff'.replace(' ', ''))
    state, error, axes, depth, deepest, index, switches, overruns, worst, feed, rapid, override_index = struct.unpack('<BBBHHIBIIHHI', status[:28])
    position = struct.unpack('<iii', status[28:])
    check((state, error, axes, depth, deepest, index, switches, overruns, worst) == (1, 0, 3, 17, 32, 123456, 6, 3, 612)
          and (feed, rapid, override_index) == (100, 100, 0) and position == (q16(1), q16(2), q16(-0.5)),
          'StatusReport example decodes')
    check(bytes.fromhex('96 00 19 00'.replace(' ', '')) == struct.pack('<HH', 150, 25), 'FeedOverride example (feed 150 %, rapid 25 %)')
    batch = bytes.fromhex('e8030000 03 03 00000100 00000200 0080ffff c801 01 00 808001 818001 7e'.replace(' ', ''))
    first, points = decode_setpoints(batch)
    check(first == 1000 and points == [(65536, 131072, -32768), (65636, 131071, -32768), (73828, 122878, -32705)],
          'SetpointBatch example decodes (zig-zag LEB128 deltas)')


class Device:
    """`curvestep device --fast` on its pseudo-terminal, and this host's end of the link."""

    def __init__(self, program, options=()):
        self.process = subprocess.Popen([program, 'device', '--fast', *options], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        path = self.process.stdout.readline().decode().strip()
        self.fd = os.open(path, os.O_RDWR | os.O_NOCTTY)
        tty.setraw(self.fd)
        self.buffer = bytearray()
        self.sequence = 0          # next command sequence number
        self.free_counter = 0      # the sequence byte of unsequenced frames
        self.setpoint_expected = 0  # next SetpointBatch sequence expected
        self.setpoints = {}        # index -> raw position
        self.credit_end = 0
        self.acked = 0             # next_expected of the last Ack
        self.acknowledge = True    # take and acknowledge SetpointBatches (False: a host that never does)

    def close(self):
        os.close(self.fd)
        self.process.kill()
        self.process.wait()

    def write(self, data):
        os.write(self.fd, data)

    def command(self, type_, message=b'', sequence=None):
        seq = self.sequence if sequence is None else sequence
        if sequence is None:
            self.sequence = (self.sequence + 1) % 256
        self.write(frame(type_, seq, message))
        return seq

    def unsequenced(self, type_, message):
        self.write(frame(type_, self.free_counter, message))
        self.free_counter = (self.free_counter + 1) % 256

    def frames(self, seconds):
        """Decoded frames (type, sequence, message) arriving within `seconds`; damaged ones as None.
        SetpointBatches are acknowledged and recorded on the way (the host's half of that stream)."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            ready, _, _ = select.select([self.fd], [], [], max(0.0, deadline - time.monotonic()))
            if not ready:
                continue
            self.buffer += os.read(self.fd, 4096)
            while b'\x00' in self.buffer:
                block, _, rest = bytes(self.buffer).partition(b'\x00')
                self.buffer = bytearray(rest)
                if not block:
                    continue
                parsed = parse_frame(cobs_decode(block))
                if parsed and parsed[0] == SETPOINT_BATCH:
                    self.on_batch(parsed)
                if parsed and parsed[0] == ACK:
                    self.acked, self.credit_end = struct.unpack('<BH', parsed[2])
                yield parsed

    def on_batch(self, parsed):
        _, sequence, message = parsed
        if not self.acknowledge:
            return
        if sequence == self.setpoint_expected:
            first, points = decode_setpoints(message)
            for k, p in enumerate(points):
                self.setpoints[first + k] = p
            self.setpoint_expected = (self.setpoint_expected + 1) % 256
        self.unsequenced(ACK, bytes([self.setpoint_expected]) + struct.pack('<H', 0))

    def wait_for(self, predicate, seconds=2.0):
        """The first frame for which predicate(type, sequence, message) holds, and all seen before it."""
        seen = []
        for parsed in self.frames(seconds):
            seen.append(parsed)
            if parsed and predicate(*parsed):
                return parsed, seen
        return None, seen

    def answers(self, seconds=0.3):
        """Every frame within `seconds` (None for damaged ones), SetpointBatches left out."""
        return [f for f in self.frames(seconds) if not (f and f[0] == SETPOINT_BATCH)]


def error_reports(frames):
    return [struct.unpack('<BHB', f[2]) for f in frames if f and f[0] == ERROR_REPORT]


def acks(frames):
    return [struct.unpack('<BH', f[2]) for f in frames if f and f[0] == ACK]


def handshake(d, session):
    """Hello; the Capabilities fields as a tuple, or None if none came."""
    d.unsequenced(HELLO, struct.pack('<HH', VERSION, session))
    caps, _ = d.wait_for(lambda t, s, m: t == CAPABILITIES)
    if caps is None:
        return None
    d.sequence = 0
    d.setpoint_expected = 0
    d.setpoints = {}
    return struct.unpack('<HHHHHBBBBIH', caps[2])


def status(d):
    """(state, error, queue depth, setpoint index) of a fresh StatusReport, or None."""
    d.command(STATUS_REQUEST)
    report, _ = d.wait_for(lambda t, s, m: t == STATUS_REPORT, 0.5)
    if report is None:
        return None
    state, error, _, depth, _, index = struct.unpack('<BBBHHI', report[2][:11])
    return state, error, depth, index


def run_job_to_end(d, seconds=10):
    """Polls status until the job ends: Idle with an empty queue after Running, every setpoint up to its index arrived."""
    running_seen = False
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        now = status(d)
        if now is None:
            continue
        state, _, depth, index = now
        running_seen = running_seen or state == 1
        # docs/protocol.md, "The end of a job": Idle with an empty queue after Running (or after setpoints arrived).
        if (running_seen or bool(d.setpoints)) and state == 0 and depth == 0 and all(i in d.setpoints for i in range(index + 1)):
            return True
    return False


def run_stream_failure_checks(program, codes):
    """Issue 24.1 and 24.2: a host that keeps talking but never acknowledges setpoints. The device is
    started with a 5 ms retransmission timeout, so its sender's 255 timeouts take about 1.3 s."""
    d = Device(program, ('--retransmit-timeout-ms', '5'))
    try:
        caps = handshake(d, 0x1357)
        check(caps is not None, 'stream failure: Hello is answered')
        if caps is None:
            return
        axes = caps[7]
        d.command(CONFIGURATION, configuration_message(axes=axes))
        d.command(SEGMENT, line_message((0.0, 0.0, 0.0), (300.0, 0.0, 0.0), feed=50.0, end_of_job=True))
        check(not error_reports(d.answers()), 'stream failure: the configuration and a 300 mm line are taken')
        d.acknowledge = False
        d.command(START)
        reports, fault = [], None
        deadline = time.monotonic() + 15
        while time.monotonic() < deadline and fault is None:
            d.command(STATUS_REQUEST)  # the host talks, so the stream's end is RetransmitLimit, not LinkTimeout
            frames = d.answers(0.05)
            reports += error_reports(frames)
            for f in frames:
                if f and f[0] == STATUS_REPORT and f[2][0] == 3:
                    fault = f[2][1]
        check([r[0] for r in reports] == [codes['RetransmitLimit']],
              'a host that talks but never acknowledges setpoints gets one ErrorReport(RetransmitLimit) (24.2), got %s' % reports)
        check(fault == codes['RetransmitLimit'], 'the StatusReport says Fault with RetransmitLimit as its last error')
        # 24.1: after Abort the session cannot stream; a new job is refused with the reason, never "Running" without motion.
        d.acknowledge = True
        d.command(ABORT)
        seq_segment = d.command(SEGMENT, line_message((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), feed=50.0, end_of_job=True))
        seq_start = d.command(START)
        frames = d.answers(0.5)
        refused = error_reports(frames)
        check(any(r[0] == codes['RetransmitLimit'] and r[2] == seq_segment for r in refused),
              'after the stream failed, a new segment is refused with RetransmitLimit (24.1)')
        check(any(r[0] == codes['RetransmitLimit'] and r[2] == seq_start for r in refused),
              'after the stream failed, Start is refused with RetransmitLimit (24.1)')
        now = status(d)
        check(now is not None and now[0] != 1, 'after the stream failed, the device never reports Running')
        # A new session restores the stream: a job runs to its end.
        caps = handshake(d, 0x2469)
        check(caps is not None, 'a new Hello after the failed stream is answered')
        # 24.10: the configuration belongs to its session.
        seq = d.command(START)
        check(any(r[0] == codes['ConfigurationMissing'] and r[2] == seq for r in error_reports(d.answers())),
              'a new session starts without a configuration: Start gets ConfigurationMissing (24.10)')
        d.command(CONFIGURATION, configuration_message(axes=axes))
        d.command(SEGMENT, line_message((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), feed=50.0, end_of_job=True))
        d.command(START)
        check(run_job_to_end(d), 'in the new session a job streams its setpoints to its end')
        check(d.setpoints and d.setpoints[max(d.setpoints)] == (q16(2.0), 0, 0), 'the new job ends at (2, 0, 0) exactly')
    finally:
        d.close()


def run_device_checks(program, codes):
    d = Device(program)
    try:
        # Before a handshake: every sequenced frame gets Nak(NotConnected).
        d.command(STATUS_REQUEST, sequence=0)
        nak, _ = d.wait_for(lambda t, s, m: t == NAK)
        check(nak is not None and nak[2][1] == codes['NotConnected'], 'not connected: a command gets Nak(NotConnected)')
        # A Hello of the wrong length: Nak(VersionMismatch), nothing changes.
        d.unsequenced(HELLO, struct.pack('<HHB', VERSION, 7, 0))
        nak, _ = d.wait_for(lambda t, s, m: t == NAK)
        check(nak is not None and nak[2][1] == codes['VersionMismatch'], 'a Hello of the wrong length gets Nak(VersionMismatch)')
        # Handshake.
        session = 0x2468
        d.unsequenced(HELLO, struct.pack('<HH', VERSION, session))
        caps, _ = d.wait_for(lambda t, s, m: t == CAPABILITIES)
        check(caps is not None, 'Hello is answered by Capabilities')
        if caps is None:
            return
        (version, echo, max_payload, queue_capacity, credit_end, total_bits, fraction_bits, axis_count, max_degree,
         tick_rate, lookahead) = struct.unpack('<HHHHHBBBBIH', caps[2])
        check(len(caps[2]) == 20 and version == VERSION and echo == session, 'Capabilities: 20 bytes, version 5, the session echoed')
        check(max_payload == 162 and (total_bits, fraction_bits) == (32, 16), 'Capabilities: max_payload 162, Q16.16')
        check(credit_end == 0, 'credit: 0 before a configuration')
        check(lookahead >= 1 and axis_count in (2, 3) and 1 <= max_degree <= 7, 'Capabilities: a planner on board, its axes and degree')
        # connected: Start and QueueSegment need a configuration.
        seq = d.command(START)
        frames = d.answers()
        check((seq + 1) % 256 in [a[0] for a in acks(frames)] and (codes['ConfigurationMissing'], 0xFFFF, seq) in error_reports(frames),
              'connected: Start gets Ack + ErrorReport(ConfigurationMissing)')
        # An undefined type is a command: Ack + ErrorReport(UnknownMessage, index = type).
        seq = d.command(0x1F)
        frames = d.answers()
        check((codes['UnknownMessage'], 0x1F, seq) in error_reports(frames), 'an undefined type gets Ack + ErrorReport(UnknownMessage, type)')
        # A malformed payload: Ack + ErrorReport(BadPayload, byte offset): reserved flag bits at offset 1.
        seq = d.command(CONFIGURATION, configuration_message(axes=axis_count, flags=0x80))
        frames = d.answers()
        check(any(a[0] == (seq + 1) % 256 for a in acks(frames)) and (codes['BadPayload'], 1, seq) in error_reports(frames),
              'BadPayload: acknowledged, then ErrorReport with the offset of the flags byte')
        # A damaged frame: Nak(expected, BadCrc), not delivered.
        damaged = bytearray(frame(STATUS_REQUEST, d.sequence, b''))
        damaged[-2] ^= 0x01
        d.write(bytes(damaged))
        frames = d.answers()
        naks = [struct.unpack('<BB', f[2]) for f in frames if f and f[0] == NAK]
        check((d.sequence, codes['BadCrc']) in naks and not any(f and f[0] == STATUS_REPORT for f in frames),
              'a damaged frame gets Nak(expected, BadCrc) and is not delivered')
        # More than 167 bytes before a delimiter: FrameTooLong, reported once (one Nak), not delivered.
        d.write(bytes([0x55]) * 200 + b'\x00')
        frames = d.answers()
        naks = [struct.unpack('<BB', f[2]) for f in frames if f and f[0] == NAK]
        # (Acks may come: the 250 ms heartbeat; none may acknowledge anything new.)
        check(naks == [(d.sequence, codes['FrameTooLong'])] and all(a[0] == d.sequence for a in acks(frames)),
              'an oversized block gets exactly one Nak(expected, FrameTooLong) and is not delivered')
        # A block that decodes to 8 or more bytes whose CRC fails: BadCrc (the checks' order).
        d.write(bytes([0x01]) * 20 + b'\x00')
        frames = d.answers()
        naks = [struct.unpack('<BB', f[2]) for f in frames if f and f[0] == NAK]
        check(naks == [(d.sequence, codes['BadCrc'])], 'a block of zeros long enough for a frame fails on its CRC: Nak(BadCrc)')
        # StatusRequest in connected: Ack + StatusReport Idle.
        d.command(STATUS_REQUEST)
        report, _ = d.wait_for(lambda t, s, m: t == STATUS_REPORT)
        check(report is not None and report[2][0] == 0, 'connected: StatusRequest gets a StatusReport, Idle')
        # The configuration: Ack, then credit = free slots / 7.
        seq = d.command(CONFIGURATION, configuration_message(axes=axis_count))
        frames = d.answers(0.5)
        check(not error_reports(frames), 'a valid MachineConfiguration is taken without an ErrorReport')
        check(d.credit_end == queue_capacity // 7, 'credit after the configuration: queue slots / 7 (%d)' % (queue_capacity // 7))
        # FeedOverride (0x19): answered by a StatusReport with the values and the setpoint they were set
        # before (0: nothing moved); out of range: InvalidArgument at the field's offset; back to 100 %.
        d.command(FEED_OVERRIDE, struct.pack('<HH', 150, 25))
        report, _ = d.wait_for(lambda t, s, m: t == STATUS_REPORT)
        check(report is not None and struct.unpack('<HHI', report[2][20:28]) == (150, 25, 0),
              'FeedOverride 150 %, 25 %: a StatusReport says 150 %, 25 %, set before setpoint 0')
        seq = d.command(FEED_OVERRIDE, struct.pack('<HH', 201, 100))
        check((codes['InvalidArgument'], 0, seq) in error_reports(d.answers()), 'a feed override of 201 % gets InvalidArgument, index 0')
        seq = d.command(FEED_OVERRIDE, struct.pack('<HH', 100, 101))
        check((codes['InvalidArgument'], 2, seq) in error_reports(d.answers()), 'a rapid override of 101 % gets InvalidArgument, index 2')
        d.command(FEED_OVERRIDE, struct.pack('<HH', 100, 100))
        d.answers()
        # Limits outside their documented ranges are refused, the configuration in force stays (24.3, 24.4).
        seq = d.command(CONFIGURATION, configuration_message(axes=axis_count, v=5e-324))
        frames = d.answers()
        check((codes['InvalidLimit'], 0, seq) in error_reports(frames), 'v_max 5e-324 gets InvalidLimit, index 0 (LimitField v_max)')
        seq = d.command(CONFIGURATION, configuration_message(axes=axis_count, rate=300))
        frames = d.answers()
        check((codes['InvalidRate'], 5, seq) in error_reports(frames),
              'a control rate the 1 MHz step timer cannot hold (300 Hz) gets InvalidRate, index 5')
        # 24.3: the document's whole rate range: 100 kHz divides the 1 MHz step timer and is taken.
        seq = d.command(CONFIGURATION, configuration_message(axes=axis_count, rate=100000))
        frames = d.answers()
        check(not error_reports(frames), 'a control rate of 100 kHz is taken (24.3)')
        d.command(CONFIGURATION, configuration_message(axes=axis_count))
        check(not error_reports(d.answers()), 'the 1 kHz configuration is taken again')
        # 24.10: a zero-length segment is DegenerateCurve, the queue stays empty.
        seq = d.command(SEGMENT, line_message((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), feed=50.0))
        frames = d.answers()
        check(any(r[0] == codes['DegenerateCurve'] and r[2] == seq for r in error_reports(frames)),
              'a zero-length line is refused with DegenerateCurve (24.10)')
        # configured: Start on an empty queue is NothingQueued.
        seq = d.command(START)
        frames = d.answers()
        check((codes['NothingQueued'], 0xFFFF, seq) in error_reports(frames), 'configured: Start on an empty queue gets NothingQueued')
        # A duplicate (an old sequence number) is acknowledged again, not executed again.
        d.command(START, sequence=seq)
        frames = d.answers()
        check(acks(frames) and acks(frames)[-1][0] == d.sequence and not error_reports(frames),
              'a duplicate command is acknowledged again without being executed')
        # A job: one line, Start after it; the setpoints end at its end point.
        end = (10.0, 0.0, 0.0)
        d.command(SEGMENT, line_message((0.0, 0.0, 0.0), end, feed=50.0, end_of_job=True))
        d.command(START)
        frames = d.answers(0.3)
        check(not error_reports(frames), 'a line and Start are taken')
        check(run_job_to_end(d), 'the job ends: Idle with an empty queue after Running, every setpoint up to its index arrived')
        indices = sorted(d.setpoints)
        check(indices == list(range(len(indices))) and len(indices) > 10, 'setpoint indices run 0, 1, 2, ... without a gap')
        if indices:
            check(d.setpoints[indices[-1]] == tuple(q16(c) for c in end), 'the last setpoint is the segment end (10, 0, 0) exactly')
            steps = [abs(d.setpoints[i + 1][0] - d.setpoints[i][0]) for i in indices[:-1]]
            check(max(steps) <= q16(50.0 / 1000) + 1, 'no setpoint moves faster than the feed (50 mm/s at 1 kHz)')
        # Abort in configured: Ack, still configured (Start on the empty queue is NothingQueued again).
        d.command(ABORT)
        seq = d.command(START)
        frames = d.answers()
        check((codes['NothingQueued'], 0xFFFF, seq) in error_reports(frames), 'after a finished job and Abort: configured again')
    finally:
        d.close()


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    program, docs_dir = sys.argv[1], sys.argv[2]
    codes = error_codes(docs_dir)
    check(all(name in codes for name in ('NotConnected', 'VersionMismatch', 'ConfigurationMissing', 'UnknownMessage', 'BadPayload',
                                         'BadCrc', 'NothingQueued', 'FrameTooLong', 'InvalidLimit',
                                         'InvalidRate', 'RetransmitLimit', 'DegenerateCurve')), 'docs/errors.md names every code this suite checks')
    document_examples()
    run_device_checks(program, codes)
    run_stream_failure_checks(program, codes)
    print('%d failed' % len(failures))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
