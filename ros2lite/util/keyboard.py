"""Single keys from a terminal. `Keyboard` reads them one at a time (the teleop demos, the
consoles' terminal views); `KeyHandlers` calls a handler for each key on a thread of its own
(`bag record`'s and `bag play`'s SPACE and arrows).

`Keyboard` switches the terminal to non-canonical, no-echo input for as long as it is open
(a `with` block), so each key arrives at once; arrow keys (``ESC [ A`` …, or ``ESC O A`` in
application mode) come back as 'up', 'down', 'right', 'left'. The saved settings are restored
on leaving the block, on an exception, and at interpreter exit. `raw=True` also turns off
the terminal's signal keys, so Ctrl-C arrives as the character '\\x03' (what
teleop_twist_keyboard expects); otherwise Ctrl-C raises KeyboardInterrupt as usual.
When stdin is not a terminal (a pipe, a file) keys are read from it unchanged.

`KeyHandlers` reads through a `Keyboard` (so Ctrl-C still raises SIGINT), each key of a burst
on its own: two arrows that arrive in one read are two presses.
"""

from __future__ import annotations

import atexit
import contextlib
import os
import select
import sys
import threading
from collections.abc import Callable

ARROWS = {'A': 'up', 'B': 'down', 'C': 'right', 'D': 'left'}
ESCAPE_WAIT = 0.05  # s: how long the rest of an escape sequence may take to arrive


def available() -> bool:
    """stdin is a terminal and we are its foreground job (changing the terminal mode from
    a background job would stop the process with SIGTTOU)."""
    try:
        fd = sys.stdin.fileno()
        return os.isatty(fd) and os.tcgetpgrp(fd) == os.getpgrp()
    except (OSError, ValueError, AttributeError):
        return False


class Keyboard:
    """The terminal on file descriptor `fd` (stdin by default), one key at a time."""

    def __init__(self, fd: int | None = None, *, raw: bool = False) -> None:
        self.fd = sys.stdin.fileno() if fd is None else fd
        self.raw = raw
        self._saved: list[int | list[bytes | int]] | None = None  # termios attributes

    def __enter__(self) -> Keyboard:
        if not os.isatty(self.fd):
            return self
        import termios

        self._saved = termios.tcgetattr(self.fd)
        mode = termios.tcgetattr(self.fd)
        mode[3] &= ~(termios.ICANON | termios.ECHO | (termios.ISIG if self.raw else 0))
        if self.raw:
            mode[0] &= ~(termios.IXON | termios.ICRNL)
        mode[6][termios.VMIN] = 1
        mode[6][termios.VTIME] = 0
        atexit.register(self.restore)
        termios.tcsetattr(self.fd, termios.TCSANOW, mode)
        return self

    def __exit__(self, *exc: object) -> None:
        self.restore()

    def restore(self) -> None:
        """Put the terminal back as it was (safe to call more than once)."""
        saved, self._saved = self._saved, None
        if saved is None:
            return
        import termios

        # a terminal that is gone (hung up) has nothing left to restore
        with contextlib.suppress(termios.error):
            termios.tcsetattr(self.fd, termios.TCSADRAIN, saved)
        atexit.unregister(self.restore)

    def _ready(self, timeout: float | None) -> bool:
        return bool(select.select([self.fd], [], [], timeout)[0])

    def _byte(self) -> str:
        data = os.read(self.fd, 1)
        if not data:
            raise EOFError('end of input')
        return data.decode('latin-1')

    def read(self, timeout: float | None = None) -> str | None:
        """The next key, or None when none came within `timeout` seconds. Raises EOFError
        at the end of a non-terminal input."""
        if not self._ready(timeout):
            return None
        key = self._byte()
        if key != '\x1b' or not self._ready(ESCAPE_WAIT):
            return key
        second = self._byte()
        if second not in '[O' or not self._ready(ESCAPE_WAIT):
            return key + second
        third = self._byte()
        return ARROWS.get(third, key + second + third)


class KeyHandlers:
    """Calls `handlers[key]()` from a background thread for each key pressed on stdin (see
    `available`), read by a `Keyboard` until `close()`."""

    def __init__(self, handlers: dict[str, Callable[[], object]]) -> None:
        self.handlers = handlers
        self._keyboard = Keyboard().__enter__()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True, name="ros2lite-keys")
        self._thread.start()

    def _run(self) -> None:
        while not self._stop.is_set():
            try:
                key = self._keyboard.read(0.1)
            except (EOFError, OSError):  # input ended, or the terminal hung up
                return
            handler = self.handlers.get(key) if key is not None else None
            if handler is not None:
                with contextlib.suppress(Exception):
                    handler()

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=1)
        self._keyboard.restore()
