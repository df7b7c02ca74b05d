"""How the CLI draws: plain lines when piped, colour and live tables only on a terminal.

The rule lives here once: extras appear only when the stream is a TTY and `NO_COLOR` is not
set, because scripts parse the plain output (ros2cli's formats) and must never see escapes.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence
from typing import TextIO


def fancy(stream: TextIO | None = None) -> bool:
    """May we draw live tables, progress and colour on `stream` (stdout by default)?"""
    out = sys.stdout if stream is None else stream
    try:
        return out.isatty() and 'NO_COLOR' not in os.environ
    except (AttributeError, ValueError):  # replaced or closed stream
        return False


def ascii_table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    """ros2cli's table: centred headers, left-justified cells, 3-space gaps, '=' rule."""
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(header)]
    head = '   '.join(h.center(w) for h, w in zip(header, widths, strict=True))
    rule = '=' * (sum(widths) + 3 * (len(widths) - 1))
    body = '\n'.join('   '.join(c.ljust(w) for c, w in zip(r, widths, strict=True)) for r in rows)
    return f'{head}\n{rule}\n{body}\n'


class LiveTable:
    """A table redrawn in place on a terminal; rows are keyed by their first cell, so a row
    shown again replaces the old one. `transient` tables vanish when closed."""

    def __init__(self, header: Sequence[str], *, transient: bool = False) -> None:
        from rich.live import Live

        self.header = list(header)
        self._rows: dict[str, Sequence[str]] = {}
        self._live = Live(auto_refresh=False, transient=transient)
        self._live.start()

    def show(self, rows: Sequence[Sequence[str]], title: str | None = None) -> None:
        """Update these rows (others stay) and redraw."""
        from rich.table import Table

        for row in rows:
            self._rows[row[0]] = row
        table = Table(*self.header, title=title)
        for row in self._rows.values():
            table.add_row(*row)
        self._live.update(table, refresh=True)

    def close(self) -> None:
        """Stop redrawing (the last table stays unless transient)."""
        self._live.stop()


class ProgressLine:
    """One status line rewritten in place on a terminal stream (stderr by default)."""

    def __init__(self, stream: TextIO | None = None) -> None:
        self.stream = sys.stderr if stream is None else stream

    def show(self, text: str) -> None:
        """Replace the line with `text`."""
        self.stream.write(f'\r{text}')
        self.stream.flush()

    def close(self) -> None:
        """End the line, so what follows starts on a fresh one."""
        self.stream.write('\n')
        self.stream.flush()
