"""What rqt_console keeps and shows: `/rosout` messages as rows, the last N of them, through
the filters a person sets (least severity, node, text) and a pause.

Both views read one `Console`; messages arrive on the executor's thread and the views read
on the main thread, so the console holds a lock and a version number that changes with
every message kept or filter set (a view redraws only when it changed).
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from ros2lite.bundled.terminal import visible
from ros2lite.logging import LoggingSeverity

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import Log

# the severities /rosout carries, each with the tint its rows are marked with (window rows'
# background, the terminal's severity cell)
SEVERITIES = ('DEBUG', 'INFO', 'WARN', 'ERROR', 'FATAL')
TINTS: dict[str, tuple[int, int, int]] = {
    'DEBUG': (0xC8, 0xD7, 0xE6),
    'INFO': (0xFF, 0xFF, 0xFF),
    'WARN': (0xFF, 0xD2, 0x4D),
    'ERROR': (0xFF, 0x8A, 0x80),
    'FATAL': (0xC0, 0x30, 0x30),
}
DEFAULT_LINES = 1000


def severity_name(level: int) -> str:
    """The name of a `/rosout` level (a level between two names counts as the lower)."""
    name = 'DEBUG'
    for candidate in SEVERITIES:
        if level >= LoggingSeverity[candidate]:
            name = candidate
    return name


def parse_severity(text: str) -> str:
    """A severity named by the user (any case, WARNING too), or ValueError."""
    name = text.strip().upper()
    name = 'WARN' if name == 'WARNING' else name
    if name not in SEVERITIES:
        raise ValueError(f"unknown severity '{text}' (one of {', '.join(SEVERITIES)})")
    return name


@dataclass(frozen=True)
class Row:
    """One log message as rqt_console lists it."""

    number: int  # in order of arrival, from 1
    severity: str
    node: str  # the logger's name, as /rosout gives it
    stamp: float  # s since the epoch
    message: str
    location: str  # file:function:line

    @classmethod
    def from_log(cls, number: int, msg: Log) -> Row:
        """A row of an rcl_interfaces/msg/Log message."""
        return cls(
            number=number,
            severity=severity_name(msg.level),
            node=msg.name,
            stamp=msg.stamp.sec + msg.stamp.nanosec / 1e9,
            message=msg.msg,
            location=f'{msg.file}:{msg.function}:{msg.line}',
        )

    def stamp_text(self) -> str:
        """The stamp as rqt_console shows it: local wall time with nanoseconds' first digits."""
        whole = int(self.stamp)
        return time.strftime('%H:%M:%S', time.localtime(whole)) + f'.{self.stamp - whole:.6f}'[2:]


@dataclass(frozen=True)
class Filters:
    """Which rows show: at least `severity`, the node's name and the message containing the
    given text (case-insensitive; empty: any)."""

    severity: str = 'DEBUG'
    node: str = ''
    text: str = ''

    def accepts(self, row: Row) -> bool:
        """Whether `row` passes every filter."""
        return (
            SEVERITIES.index(row.severity) >= SEVERITIES.index(self.severity)
            and self.node.lower() in row.node.lower()
            and self.text.lower() in row.message.lower()
        )


class Console:
    """The last `lines` messages, filters and pause; safe to use from two threads."""

    def __init__(self, lines: int = DEFAULT_LINES, filters: Filters | None = None) -> None:
        if lines < 1:
            raise ValueError(f'--lines must be at least 1, not {lines}')
        self._lock = threading.Lock()
        self._rows: deque[Row] = deque(maxlen=lines)
        self._received = 0
        self._filters = filters or Filters()
        self._paused = False
        self._frozen: tuple[Row, ...] = ()  # what showed when the pause began
        self._version = 0

    def add(self, msg: Log) -> Row:
        """Keep a `/rosout` message (the oldest goes when the console is full)."""
        with self._lock:
            self._received += 1
            row = Row.from_log(self._received, msg)
            self._rows.append(row)
            if not self._paused:
                self._version += 1
            return row

    def extend(self, msgs: Iterable[Log]) -> None:
        """Keep several messages in order."""
        for msg in msgs:
            self.add(msg)

    @property
    def version(self) -> int:
        """Changes whenever what the views show may have changed."""
        with self._lock:
            return self._version

    @property
    def filters(self) -> Filters:
        with self._lock:
            return self._filters

    def set_filters(self, **changes: str) -> None:
        """Change some filters (`severity`, `node`, `text`); a bad severity raises ValueError."""
        if 'severity' in changes:
            changes['severity'] = parse_severity(changes['severity'])
        with self._lock:
            self._filters = replace(self._filters, **changes)
            self._version += 1

    @property
    def paused(self) -> bool:
        with self._lock:
            return self._paused

    def toggle_pause(self) -> bool:
        """Pause (the view stands still, messages are still kept) or resume; the new state."""
        with self._lock:
            self._paused = not self._paused
            self._frozen = tuple(self._rows) if self._paused else ()
            self._version += 1
            return self._paused

    def clear(self) -> None:
        """Forget every message kept so far."""
        with self._lock:
            self._rows.clear()
            self._frozen = ()
            self._version += 1

    def shown(self, last: int | None = None) -> tuple[list[Row], int]:
        """The rows that pass the filters (the last `last` of them), and how many are kept."""
        with self._lock:
            rows = self._frozen if self._paused else tuple(self._rows)
            filters = self._filters
            kept = len(self._rows)
        matching = [row for row in rows if filters.accepts(row)]
        if last is not None:
            matching = matching[-last:] if last > 0 else []
        return matching, kept

    def status(self, shown: int, kept: int) -> str:
        """The line under the table: counts, filters, pause."""
        f = self.filters
        parts = [f'Displaying {shown} of {kept} messages', f'severity >= {f.severity}']
        if f.node:
            parts.append(f'node ~ {f.node!r}')
        if f.text:
            parts.append(f'text ~ {f.text!r}')
        if self.paused:
            parts.append('PAUSED')
        return '  |  '.join(parts)


# the table's columns, as rqt_console names them, and how wide each is at most (0: the rest)
COLUMNS = ('#', 'Severity', 'Node', 'Stamp', 'Message', 'Location')
_WIDEST = {'#': 6, 'Severity': 8, 'Node': 24, 'Stamp': 15, 'Message': 0, 'Location': 40}


def cells(row: Row) -> tuple[str, ...]:
    """A row's text, column by column; what came from `/rosout` with its control characters
    escaped, so a hostile line (an OSC retitling the terminal, a CSI blanking it) is shown,
    never obeyed."""
    return (
        str(row.number),
        row.severity,
        visible(row.node),
        row.stamp_text(),
        visible(row.message.replace('\n', ' ')),
        visible(row.location),
    )


def widths(rows: list[Row], total: int) -> list[int]:
    """Column widths for `rows` in `total` characters (a space between columns): the fixed
    columns as wide as their text needs (up to their most), the message the rest; the
    location is left out (width 0) when the message would get under 30 characters."""
    need = [len(name) for name in COLUMNS]
    for row in rows:
        need = [max(n, len(text)) for n, text in zip(need, cells(row), strict=True)]
    out = [min(n, _WIDEST[name] or n) for n, name in zip(need, COLUMNS, strict=True)]
    message = COLUMNS.index('Message')
    rest = total - (sum(out) - out[message]) - (len(COLUMNS) - 1)
    if rest < 30:  # no room for the location
        rest += out[-1] + 1
        out[-1] = 0
    out[message] = max(rest, 1)
    return out


def line(texts: tuple[str, ...], sizes: list[int]) -> str:
    """Texts cut or padded to their column's width (columns of width 0 left out)."""
    parts = []
    for text, size in zip(texts, sizes, strict=True):
        if size <= 0:
            continue
        parts.append(text[: size - 1] + '…' if len(text) > size else text.ljust(size))
    return ' '.join(parts)
