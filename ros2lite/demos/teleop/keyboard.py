"""Single key presses from a terminal, with the terminal put back however the program ends.

`Keyboard` switches the terminal to non-canonical, no-echo input for as long as it is open
(a `with` block), so each key arrives at once; arrow keys (``ESC [ A`` …, or ``ESC O A`` in
application mode) come back as 'up', 'down', 'right', 'left'. The saved settings are restored
on leaving the block, on an exception, and at interpreter exit. `raw=True` also turns off
the terminal's signal keys, so Ctrl-C arrives as the character '\\x03' (what
teleop_twist_keyboard expects); otherwise Ctrl-C raises KeyboardInterrupt as usual.
When stdin is not a terminal (a pipe, a file) keys are read from it unchanged.
"""

from __future__ import annotations

import atexit
import contextlib
import os
import select
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ros2lite.node import Node

ARROWS = {'A': 'up', 'B': 'down', 'C': 'right', 'D': 'left'}
ESCAPE_WAIT = 0.05  # s: how long the rest of an escape sequence may take to arrive


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


def key_loop(node: Node, banner: str, handle: Callable[[str], bool], *, raw: bool = False) -> None:
    """Show `banner`, then pass each key to `handle` until it returns False, input ends or the
    context shuts down, with `node` spinning in the background and the terminal restored on
    every way out (what every teleop program does)."""
    from ros2lite.demos.teleop.spinning import BackgroundSpin

    context = node.context
    with BackgroundSpin(node), Keyboard(raw=raw) as keyboard:
        print(banner, flush=True)
        while context.ok():
            try:
                key = keyboard.read(0.1)
            except EOFError:
                return
            if key is not None and not handle(key):
                return
