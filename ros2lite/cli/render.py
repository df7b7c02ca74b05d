"""How the CLI draws: plain lines when piped, colour and live tables only on a terminal.

The rule lives here once: extras appear only when the stream is a TTY and `NO_COLOR` is not
set, because scripts parse the plain output (ros2cli's formats) and must never see escapes.
Names from outside (the graph, bags, datagrams) go to a terminal through :func:`echo`, which
shows their control characters escaped: a name must not clear the screen or retitle it.
"""

from __future__ import annotations

import os
import re
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING, TextIO

import click

from .errors import CliError

if TYPE_CHECKING:
    from ros2lite.interfaces import Message
    from ros2lite.monitor.plot import Plot
    from ros2lite.qos import QoSProfile
    from ros2lite.topic_endpoint_info import TopicEndpointInfo

    from .options import MessageFormat

# C0 and C1 controls but newline and tab, DEL, and the bidirectional overrides that reorder
# what a terminal shows
_UNSAFE = re.compile('[\x00-\x08\x0b-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]')


def fancy(stream: TextIO | None = None) -> bool:
    """May we draw live tables, progress and colour on `stream` (stdout by default)?"""
    return _tty(sys.stdout if stream is None else stream) and 'NO_COLOR' not in os.environ


def _tty(stream: TextIO) -> bool:
    try:
        return stream.isatty()
    except (AttributeError, ValueError):  # replaced or closed stream
        return False


def _escaped(match: re.Match[str]) -> str:
    code = ord(match.group())
    return f'\\x{code:02x}' if code < 0x100 else f'\\u{code:04x}'


def shown(text: str, stream: TextIO | None = None) -> str:
    """`text` as it may reach `stream` (stdout by default): on a terminal, control characters
    are written as escapes (``\\x1b``); piped, it stays byte for byte what came."""
    out = sys.stdout if stream is None else stream
    return _UNSAFE.sub(_escaped, text) if _tty(out) else text


def echo(text: str, *, err: bool = False, nl: bool = True) -> None:
    """``click.echo`` of text that holds names from outside (see :func:`shown`)."""
    click.echo(shown(text, sys.stderr if err else sys.stdout), err=err, nl=nl)


def format_size(size: float) -> str:
    """rosbag2's 1024-based size (`bag info`, the recorder's live table): bytes without
    decimals, then one decimal."""
    units = ['B', 'KiB', 'MiB', 'GiB', 'TiB']
    i = 0
    while size >= 1024 and i < len(units) - 1:
        size /= 1024
        i += 1
    return f'{size:.0f} {units[i]}' if i == 0 else f'{size:.1f} {units[i]}'


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


def print_json(obj: object) -> None:
    """One JSON document of a verb's `--json` (compact, one line: `jq` pretty-prints it)."""
    from ros2lite.interfaces.json_form import dumps

    sys.stdout.write(dumps(obj) + '\n')


def print_json_line(obj: object) -> None:
    """One NDJSON line of a stream, flushed at once: a reader of the pipe (`jq`, `head -1`)
    sees each object as it happens."""
    print_json(obj)
    sys.stdout.flush()


def qos_json(qos: QoSProfile) -> dict[str, object]:
    """A QoS profile in the schema: policies by name, durations in integer nanoseconds."""
    return {
        'reliability': qos.reliability.name,
        'history': qos.history.name,
        'depth': qos.depth,
        'durability': qos.durability.name,
        'lifespan_ns': qos.lifespan.nanoseconds,
        'deadline_ns': qos.deadline.nanoseconds,
        'liveliness': qos.liveliness.name,
        'liveliness_lease_duration_ns': qos.liveliness_lease_duration.nanoseconds,
    }


def endpoint_json(info: TopicEndpointInfo) -> dict[str, object]:
    """One endpoint of `topic info -v` (and `node info`'s peers) in the schema."""
    from ros2lite.topic_endpoint_info import format_gid

    return {
        'node_name': info.node_name,
        'node_namespace': info.node_namespace,
        'topic_type': info.topic_type,
        'topic_type_hash': info.topic_type_hash or None,
        'endpoint_type': info.endpoint_type.name,
        'gid': format_gid(info.endpoint_gid),
        'qos': qos_json(info.qos_profile),
    }


def names_json(names_and_types: list[tuple[str, list[str]]], count: bool) -> object:
    """The `--json` of the list and find verbs: `{"count": N}` or `[{"name", "types"}…]`."""
    if count:
        return {'count': len(names_and_types)}
    return [{'name': n, 'types': t} for n, t in names_and_types]


def print_names(
    names_and_types: list[tuple[str, list[str]]], count: bool, types: bool, as_json: bool = False
) -> None:
    """What the list and find verbs print: how many there are, or one name a line (with
    `[type, …]` when asked); `as_json`: `names_json`'s document."""
    if as_json:
        print_json(names_json(names_and_types, count))
    elif count:
        click.echo(len(names_and_types))
    elif names_and_types:
        echo('\n'.join(f'{n} [{", ".join(t)}]' if types else n for n, t in names_and_types))


def print_event(
    msg: Message, fmt: MessageFormat, head: str = '', as_json: dict[str, object] | None = None
) -> None:
    """Print one service event (or any message) as `service echo` and `action echo` do:
    `head`, the message, then `---` (a CSV line ends with its newline alone). `as_json`:
    an NDJSON line instead, the message under "message" beside those keys (none: the
    message alone)."""
    from ros2lite.service_introspection import format_event

    if as_json is not None:
        from ros2lite.interfaces.json_form import message_to_json

        body = message_to_json(msg, no_arr=fmt['no_arr'], no_str=fmt['no_str'])
        print_json_line({**as_json, 'message': body} if as_json else body)
        return

    text = format_event(msg, **fmt)
    sys.stdout.write(head + text + ('\n' if fmt['csv'] else '---\n'))


# -- plots (`topic plot`, `bag plot`) ----------------------------------------------------------

_ALT_SCREEN_ON = '\x1b[?1049h\x1b[?25l'
_ALT_SCREEN_OFF = '\x1b[?25h\x1b[?1049l'


def _chart_text(plot: Plot, window: float | None, width: int, height: int, colour: bool) -> str:
    from ros2lite.monitor.chart import braille
    from ros2lite.monitor.plot import to_chart

    return braille(to_chart(plot, window=window), width, height, colour=colour)


class PlotScreen:
    """A live plot on the terminal's alternate screen, redrawn in place (so the scrollback
    stays clean); on `close` the last picture is printed on the normal screen."""

    def __init__(self, stream: TextIO | None = None) -> None:
        self.stream = sys.stdout if stream is None else stream
        self.stream.write(_ALT_SCREEN_ON)
        self.stream.flush()

    def _size(self) -> tuple[int, int]:
        import shutil

        try:
            size = os.get_terminal_size(self.stream.fileno())
        except (OSError, ValueError):
            size = shutil.get_terminal_size()
        # a terminal that says 0x0 (a bare pseudo-terminal) gets the usual 80x24
        return size.columns or 80, size.lines or 24

    def show(self, plot: Plot, window: float | None) -> None:
        """Draw `plot` as it is now over the whole screen."""
        width, height = self._size()
        text = _chart_text(plot, window, width, height - 1, True)
        lines = text.split('\n')
        self.stream.write('\x1b[H' + '\x1b[K\n'.join(lines) + '\x1b[K\x1b[J')
        self.stream.flush()

    def close(self, plot: Plot, window: float | None) -> None:
        """Back to the normal screen, with the last picture left on it."""
        self.stream.write(_ALT_SCREEN_OFF)
        width, height = self._size()
        self.stream.write(
            _chart_text(plot, window, width, max(min(height - 5, 30), 8), True) + '\n'
        )
        self.stream.flush()


def print_chart(plot: Plot, window: float | None, stream: TextIO | None = None) -> None:
    """The plot once, as plain braille text (80x24 unless the terminal says otherwise)."""
    import shutil

    out = sys.stdout if stream is None else stream
    width, height = shutil.get_terminal_size((80, 24))
    out.write(_chart_text(plot, window, width, height - 1, fancy(out)) + '\n')
    out.flush()


def write_plot(plot: Plot, paths: Sequence[str], size: tuple[int, int]) -> None:
    """Write the whole plot to each picture file (PNG or SVG by suffix); one line each."""
    from ros2lite.monitor.plot import save_picture, to_chart

    chart = to_chart(plot, window=None)
    for path in paths:
        try:
            save_picture(chart, path, size)
        except OSError as e:
            raise CliError(f"cannot write '{path}': {e.strerror or e}") from None
        click.echo(f"Wrote {path} ({plot.messages} messages)", err=True)
