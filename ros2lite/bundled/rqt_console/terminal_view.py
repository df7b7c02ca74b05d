"""rqt_console on the terminal: the newest messages that pass the filters as a table filling
the screen, each severity in its tint, a status line, and keys to pause, filter and clear."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable

from ros2lite.bundled.display import DisplayError
from ros2lite.bundled.rqt_console.model import (
    COLUMNS,
    SEVERITIES,
    TINTS,
    Console,
    cells,
    line,
    widths,
)
from ros2lite.bundled.terminal import BOLD, RESET, LivePicture, rgb, terminal_size

KEYS = 'p pause · 1-5 least severity · n node · / text · c clear · q quit'
_EDITED = {'n': 'node', '/': 'text'}  # key -> the filter it edits
_ERASE = ('\x7f', '\x08')


class ConsoleTerminal:
    """The console on the terminal; `run` until `q`, Ctrl-C or `ok()` turns False."""

    def __init__(self, console: Console) -> None:
        if not sys.stdout.isatty():
            raise DisplayError('cannot draw on the terminal: standard output is not a terminal')
        self.console = console
        self.editing: str | None = None  # the filter being typed ('node' or 'text')
        self._before = ''  # its value before, for Esc

    def picture(self, width: int, height: int) -> str:
        """The screen: title, column names, as many rows as fit, status (and the filter being
        typed), cropped to `width` x `height` cells."""
        room = max(height - 4, 0)
        rows, kept = self.console.shown(last=room)
        sizes = widths(rows, width)
        at = COLUMNS.index('Severity')
        lines = [BOLD + f'rqt_console  ({KEYS})'[:width] + RESET, BOLD + line(COLUMNS, sizes)]
        for row in rows:
            texts = cells(row)
            parts = [line(texts[:at], sizes[:at])] if at else []
            tint = rgb((0, 0, 0), TINTS[row.severity])
            parts.append(tint + line(texts[at : at + 1], sizes[at : at + 1]) + RESET)
            parts.append(line(texts[at + 1 :], sizes[at + 1 :]))
            lines.append(' '.join(parts))
        lines += [''] * (room - len(rows))
        status = self.console.status(len(rows), kept)
        if self.editing is not None:
            status = f'{self.editing} filter: {getattr(self.console.filters, self.editing)}▏'
        lines.append(BOLD + status[:width] + RESET)
        return '\n'.join(lines)

    def key(self, key: str) -> bool:
        """Act on one key; False when it asks to quit."""
        console = self.console
        if self.editing is not None:
            value = getattr(console.filters, self.editing)
            if key in ('\n', '\r'):
                self.editing = None
                console.set_filters()  # redraw without the prompt
            elif key == '\x1b':
                console.set_filters(**{self.editing: self._before})
                self.editing = None
            elif key in _ERASE:
                console.set_filters(**{self.editing: value[:-1]})
            elif key.isprintable() and len(key) == 1:
                console.set_filters(**{self.editing: value + key})
            return True
        if key == 'q':
            return False
        if key in ('p', ' '):
            console.toggle_pause()
        elif key == 'c':
            console.clear()
        elif key in '12345' and len(key) == 1:
            console.set_filters(severity=SEVERITIES[int(key) - 1])
        elif key in _EDITED:
            self.editing = _EDITED[key]
            self._before = getattr(console.filters, self.editing)
            console.set_filters()
        return True

    def run(self, ok: Callable[[], bool], period: float) -> None:
        """Redraw when the console or the terminal's size changed; read keys meanwhile."""
        from ros2lite.util.keyboard import Keyboard

        shown = None
        keys = True  # until the input ends (then the table is only shown)
        with LivePicture(sys.stdout) as live, Keyboard() as keyboard:
            while ok():
                state = (self.console.version, terminal_size(sys.stdout))
                if state != shown:
                    shown = state
                    width, height = state[1]
                    # one line short of the screen, so the picture never scrolls it
                    live.show(self.picture(width, height - 1))
                key = None
                if keys:
                    try:
                        key = keyboard.read(period)
                    except EOFError:
                        keys = False
                else:
                    time.sleep(period)
                if key is not None and not self.key(key):
                    return
