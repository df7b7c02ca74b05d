"""A program run on a pseudo-terminal, as a person at a terminal runs it: keys in, the screen's
bytes out, Ctrl-C through the terminal's own signal key, and its settings readable."""

from __future__ import annotations

import contextlib
import os
import pty
import re
import signal
import struct
import sys
import termios
import threading
import time
from typing import Any

ANSI = re.compile(r'\x1b\[[0-9;?]*[A-Za-z]')


class PtyProcess:
    """`argv` as the session leader of a new pseudo-terminal of `rows` x `cols`."""

    def __init__(
        self, argv: list[str], env: dict[str, str] | None = None, rows: int = 24, cols: int = 80
    ) -> None:
        env = dict(os.environ if env is None else env)
        env.setdefault('TERM', 'xterm-256color')
        pid, fd = pty.fork()
        if pid == 0:  # the child: set the terminal's size, then become the program
            try:
                import fcntl

                fcntl.ioctl(0, termios.TIOCSWINSZ, struct.pack('HHHH', rows, cols, 0, 0))
                os.execvpe(argv[0], argv, env)
            finally:
                os._exit(127)
        self.pid = pid
        self.fd = fd
        self.returncode: int | None = None
        self._output = bytearray()
        self._lock = threading.Lock()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        while True:
            try:
                data = os.read(self.fd, 65536)
            except OSError:
                return
            if not data:
                return
            with self._lock:
                self._output += data

    @property
    def output(self) -> str:
        with self._lock:
            return self._output.decode('utf-8', 'replace')

    def raw_output(self) -> bytes:
        with self._lock:
            return bytes(self._output)

    @property
    def plain(self) -> str:
        """The output without terminal escape sequences (what the characters say)."""
        return ANSI.sub('', self.output)

    def send(self, data: str | bytes) -> None:
        os.write(self.fd, data.encode() if isinstance(data, str) else data)

    def expect(
        self, pattern: str, timeout: float = 20.0, start: int = 0, plain: bool = False
    ) -> re.Match[str]:
        """Wait until the output (from character `start`; without escapes if `plain`)
        matches `pattern`."""
        regex = re.compile(pattern)
        deadline = time.monotonic() + timeout
        while True:
            match = regex.search(self.plain if plain else self.output, start)
            if match:
                return match
            if time.monotonic() > deadline or (self.poll() is not None and not match):
                # one last look: the reader may still hold the final bytes
                time.sleep(0.2)
                match = regex.search(self.plain if plain else self.output, start)
                if match:
                    return match
                raise AssertionError(f'{pattern!r} not in output:\n{self.output[-3000:]}')
            time.sleep(0.02)

    def attrs(self) -> list[Any]:
        """The terminal's settings (termios), as the program left them."""
        return termios.tcgetattr(self.fd)

    def poll(self) -> int | None:
        if self.returncode is None:
            pid, status = os.waitpid(self.pid, os.WNOHANG)
            if pid:
                self.returncode = os.waitstatus_to_exitcode(status)
        return self.returncode

    def wait(self, timeout: float = 20.0) -> int:
        deadline = time.monotonic() + timeout
        while self.poll() is None:
            if time.monotonic() > deadline:
                raise AssertionError(f'still running; output:\n{self.output[-3000:]}')
            time.sleep(0.02)
        assert self.returncode is not None
        return self.returncode

    def close(self) -> None:
        if self.poll() is None:
            with contextlib.suppress(ProcessLookupError):
                os.kill(self.pid, signal.SIGKILL)
            with contextlib.suppress(ChildProcessError):
                os.waitpid(self.pid, 0)
        with contextlib.suppress(OSError):
            os.close(self.fd)


def ros2lite_argv(*args: str) -> list[str]:
    return [sys.executable, '-m', 'ros2lite', *args]
