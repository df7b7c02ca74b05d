"""Single keys from a terminal (SPACE, arrows) for `bag record` and `bag play`.

The terminal is put in cbreak mode (no line editing, no echo; Ctrl-C still raises SIGINT)
and restored on close. Arrow keys arrive as escape sequences and are named 'right', 'up' …
"""

from __future__ import annotations

import contextlib
import os
import select
import sys
import threading
from collections.abc import Callable

_ARROWS = {b"\x1b[A": "up", b"\x1b[B": "down", b"\x1b[C": "right", b"\x1b[D": "left"}


def available() -> bool:
    """stdin is a terminal and we are its foreground job (changing the terminal mode from
    a background job would stop the process with SIGTTOU)."""
    try:
        fd = sys.stdin.fileno()
        return os.isatty(fd) and os.tcgetpgrp(fd) == os.getpgrp()
    except (OSError, ValueError, AttributeError):
        return False


class Keyboard:
    """Calls `handlers[key]()` from a background thread for each key pressed."""

    def __init__(self, handlers: dict[str, Callable[[], object]]) -> None:
        import termios
        import tty

        self.handlers = handlers
        self._fd = sys.stdin.fileno()
        self._saved = termios.tcgetattr(self._fd)
        tty.setcbreak(self._fd)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True, name="ros2lite-keys")
        self._thread.start()

    def _run(self) -> None:
        while not self._stop.is_set():
            ready, _, _ = select.select([self._fd], [], [], 0.1)
            if not ready:
                continue
            data = os.read(self._fd, 16)
            if not data:
                return
            key = (
                _ARROWS.get(data[:3])
                if data.startswith(b"\x1b")
                else data[:1].decode(errors="replace")
            )
            handler = self.handlers.get(key or "")
            if handler is not None:
                with contextlib.suppress(Exception):
                    handler()

    def close(self) -> None:
        import termios

        self._stop.set()
        self._thread.join(timeout=1)
        termios.tcsetattr(self._fd, termios.TCSADRAIN, self._saved)
