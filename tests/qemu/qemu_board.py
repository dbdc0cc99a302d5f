#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs a bare-metal curvestep image in qemu-system-arm with its USART1 on a pseudo-terminal
(-serial pty) and talks to it like a host would. Imported by the QEMU tests and the HIL harness;
run directly for a session:  qemu_board.py <machine> <image.elf>  (prints the pty path, Ctrl-C stops)."""
import os
import re
import select
import signal
import socket
import subprocess
import sys
import termios
import time
import tty

# The QEMU machine each board's images run on (stm32f2-m3: the Cortex-M3 build on the F205).
MACHINES = {"stm32f1": "stm32vldiscovery", "stm32f4": "netduinoplus2", "stm32f2-m3": "netduino2"}


class QemuBoard:
    """One emulated board. Use as a context manager; QEMU is always killed on exit."""

    def __init__(self, machine, elf, extra=(), log=None, wall_limit=60.0, open_pty=True):
        self.machine, self.elf, self.extra, self.log, self.wall_limit = machine, elf, list(extra), log, wall_limit
        self.open_pty = open_pty  # False: leave the pty to another program (a HIL host)
        self.process = None
        self.fd = None
        self.received = b""

    def __enter__(self):
        command = ["qemu-system-arm", "-M", self.machine, "-display", "none", "-monitor", "none",
                   "-serial", "pty", "-kernel", self.elf] + self.extra
        if self.log:
            command += ["-d", "unimp,guest_errors", "-D", self.log]
        self.process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                        start_new_session=True)
        self.started = time.monotonic()
        banner = b""
        while True:
            ready, _, _ = select.select([self.process.stdout], [], [], 10.0)
            if not ready:
                raise RuntimeError("qemu printed no pty path within 10 s")
            chunk = os.read(self.process.stdout.fileno(), 4096)
            if not chunk:
                raise RuntimeError("qemu exited: " + banner.decode(errors="replace"))
            banner += chunk
            match = re.search(rb"char device redirected to (/dev/pts/\d+)", banner)
            if match:
                self.pty = match.group(1).decode()
                break
        if not self.open_pty:
            return self
        self.fd = os.open(self.pty, os.O_RDWR | os.O_NOCTTY)
        tty.setraw(self.fd)
        attributes = termios.tcgetattr(self.fd)
        attributes[3] &= ~termios.ECHO
        termios.tcsetattr(self.fd, termios.TCSANOW, attributes)
        return self

    def __exit__(self, *exc):
        if self.fd is not None:
            os.close(self.fd)
        if self.process and self.process.poll() is None:
            os.killpg(self.process.pid, signal.SIGKILL)
        if self.process:
            self.process.wait()
        return False

    def send(self, data):
        os.write(self.fd, data if isinstance(data, bytes) else data.encode())

    def expect(self, pattern, timeout=10.0):
        """Waits until `pattern` (bytes regex) matches the unread input; returns the match and consumes
        the input up to its end."""
        deadline = time.monotonic() + timeout
        regex = re.compile(pattern if isinstance(pattern, bytes) else pattern.encode())
        while True:
            match = regex.search(self.received)
            if match:
                self.received = self.received[match.end():]
                return match
            self._read_until(deadline, pattern)

    def _read_until(self, deadline, what):
        remaining = deadline - time.monotonic()
        if remaining <= 0 or time.monotonic() - self.started > self.wall_limit:
            raise TimeoutError(f"timeout waiting for {what!r}; received {self.received[-400:]!r}")
        ready, _, _ = select.select([self.fd], [], [], min(remaining, 0.5))
        if ready:
            try:
                self.received += os.read(self.fd, 4096)
            except OSError as error:
                raise RuntimeError(f"pty read failed: {error}") from error

    def handshake(self, command="hello", answer=rb"hello from \w+[^\r\n]*\r\n", timeout=15.0):
        """QEMU drops output until it notices the pty is open (it polls once a second): repeat
        `command` until `answer` arrives."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            self.send(command + "\n")
            try:
                return self.expect(answer, timeout=0.7)
            except TimeoutError:
                continue
        raise TimeoutError(f"no answer to {command!r}; received {self.received[-400:]!r}")


def curvestep_can_stream(curvestep):
    """True if `curvestep` has the `stream` subcommand; else prints the SKIP line (the tests then exit 77)."""
    probe = subprocess.run([curvestep, "stream", "--help"], capture_output=True, text=True, timeout=30)
    if probe.returncode != 0:
        print("SKIP: this curvestep has no stream subcommand")
        return False
    return True


class QemuMonitor:
    """The QEMU monitor on a unix socket (`-monitor unix:PATH,server,nowait`), one connection kept
    open: guest physical memory and memory-mapped registers read with `xp`."""

    PROMPT = b"(qemu) "

    def __init__(self, path, timeout=10.0):
        deadline = time.monotonic() + timeout
        while True:
            try:
                self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
                self.sock.connect(path)
                break
            except OSError:
                self.sock.close()
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.1)
        self.timeout = timeout
        self._until_prompt()  # the greeting

    def close(self):
        self.sock.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def _until_prompt(self):
        data, deadline = b"", time.monotonic() + self.timeout
        while not data.endswith(self.PROMPT):
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError(f"no monitor prompt; received {data[-200:]!r}")
            self.sock.settimeout(remaining)
            chunk = self.sock.recv(65536)
            if not chunk:
                raise RuntimeError("the monitor closed its socket")
            data += chunk
        return data.decode(errors="replace")

    def words(self, address, count):
        """`count` 32-bit words of guest physical memory (or registers) from `address`."""
        self.sock.sendall(f"xp /{count}wx 0x{address:08x}\n".encode())
        text = self._until_prompt()
        words = [int(w, 16) for line in text.splitlines() if re.match(r"^[0-9a-f]{8,16}:", line.strip())
                 for w in re.findall(r"0x([0-9a-f]{8})\b", line.split(":", 1)[1])]
        if len(words) < count:
            raise RuntimeError(f"monitor returned {len(words)} of {count} words: {text[-300:]!r}")
        return words[:count]


def read_words(monitor_path, address, count):
    """Guest memory words through the QEMU monitor's `xp` (one connection)."""
    with QemuMonitor(monitor_path) as monitor:
        return monitor.words(address, count)


if __name__ == "__main__":
    with QemuBoard(sys.argv[1], sys.argv[2], wall_limit=1e9, open_pty=False) as board:
        print(board.pty, flush=True)
        try:
            board.process.wait()
        except KeyboardInterrupt:
            pass
