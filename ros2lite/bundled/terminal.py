"""A live picture at the bottom of a terminal, in plain ANSI escape sequences.

The demos' terminal views (turtlesim's canvas, rqt_graph's boxes) redraw one picture in place
and print log lines above it. They need no more than this: colours (SGR, 24-bit), moving the
cursor back over the last picture, and the terminal's size — so the library stays free of the
CLI's rendering packages.
"""

from __future__ import annotations

import os
import re
import shutil
from typing import TextIO

__all__ = ['BOLD', 'RESET', 'LivePicture', 'rgb', 'terminal_size', 'visible']

RESET = '\x1b[0m'
BOLD = '\x1b[1m'
_HIDE_CURSOR = '\x1b[?25l'
_SHOW_CURSOR = '\x1b[?25h'
_CLEAR_BELOW = '\x1b[J'


# what must not reach a terminal from outside: C0 and C1 controls (ESC starts CSI and OSC
# sequences), DEL, and the bidirectional overrides that reorder what is shown
_UNSAFE = re.compile('[\x00-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]')


def _escaped(match: re.Match[str]) -> str:
    code = ord(match.group())
    return f'\\x{code:02x}' if code < 0x100 else f'\\u{code:04x}'


def visible(text: str) -> str:
    """`text` from outside (a log line, a frame name) as a view may show it: every control
    character written as an escape (`\\x1b`), so it can never move the cursor, retitle or
    blank the terminal."""
    return _UNSAFE.sub(_escaped, text)


def rgb(fg: tuple[int, int, int], bg: tuple[int, int, int] | None = None) -> str:
    """The SGR sequence for a 24-bit foreground (and background) colour."""
    code = f'\x1b[38;2;{fg[0]};{fg[1]};{fg[2]}'
    if bg is not None:
        code += f';48;2;{bg[0]};{bg[1]};{bg[2]}'
    return code + 'm'


def terminal_size(stream: TextIO) -> tuple[int, int]:
    """(columns, lines) of the terminal behind `stream` (80x24 when it cannot say)."""
    try:
        size = os.get_terminal_size(stream.fileno())
    except (OSError, ValueError):
        size = shutil.get_terminal_size()
    return size.columns, size.lines


class LivePicture:
    """The picture last drawn stays at the bottom; `show` replaces it, `print_above` puts
    lines of text above it. Use as a context manager: the cursor is hidden meanwhile and the
    last picture is left on the screen."""

    def __init__(self, stream: TextIO) -> None:
        self.stream = stream
        self._picture = ''
        self._height = 0  # lines the picture on screen takes

    def __enter__(self) -> LivePicture:
        self.stream.write(_HIDE_CURSOR)
        self.stream.flush()
        return self

    def __exit__(self, *exc: object) -> None:
        self.stream.write(RESET + _SHOW_CURSOR + '\n')
        self.stream.flush()

    def _back(self) -> str:
        # to the first line of the picture on screen, then erase it and all below
        up = f'\x1b[{self._height - 1}F' if self._height > 1 else '\r'
        return (up if self._height else '') + _CLEAR_BELOW

    def show(self, picture: str) -> None:
        """Draw `picture` (lines joined by newlines, no newline at the end) in place of the
        last one."""
        self.stream.write(self._back() + picture + RESET)
        self.stream.flush()
        self._picture = picture
        self._height = picture.count('\n') + 1

    def print_above(self, lines: list[str]) -> None:
        """Print `lines` where the picture was, then the picture again below them."""
        self.stream.write(self._back() + RESET + ''.join(line + '\n' for line in lines))
        self._height = 0
        if self._picture:
            self.show(self._picture)
        else:
            self.stream.flush()
