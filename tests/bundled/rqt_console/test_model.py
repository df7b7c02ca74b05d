"""What rqt_console keeps and shows, without a graph: the last N, the filters, the pause, and
the columns fitted to a width."""

from __future__ import annotations

import pytest

from ros2lite.bundled.rqt_console.model import Console, Filters, cells, line, parse_severity, widths
from ros2lite.msgs.builtin_interfaces.msg import Time
from ros2lite.msgs.rcl_interfaces.msg import Log


def log(level: int, name: str, msg: str) -> Log:
    return Log(
        stamp=Time(sec=1_700_000_000, nanosec=250_000_000),
        level=level,
        name=name,
        msg=msg,
        file='talker.py',
        function='tick',
        line=42,
    )


def test_last_lines_and_filters() -> None:
    console = Console(lines=3)
    console.extend(
        [log(20, 'talker', 'hello 1'), log(30, 'battery', 'low battery'), log(10, 'talker', 'x')]
    )
    console.add(log(40, 'motor', 'stalled'))
    rows, kept = console.shown()
    assert kept == 3 and [r.number for r in rows] == [2, 3, 4]  # the oldest went
    assert [r.severity for r in rows] == ['WARN', 'DEBUG', 'ERROR']
    console.set_filters(severity='warning')
    assert [r.message for r in console.shown()[0]] == ['low battery', 'stalled']
    console.set_filters(node='MOT')
    assert [r.message for r in console.shown()[0]] == ['stalled']
    console.set_filters(node='', severity='DEBUG', text='BATT')
    assert [r.message for r in console.shown()[0]] == ['low battery']
    assert console.shown(last=0)[0] == []
    assert 'Displaying 1 of 3 messages' in console.status(1, 3)
    with pytest.raises(ValueError, match="unknown severity 'LOUD'"):
        parse_severity('LOUD')
    with pytest.raises(ValueError):
        Console(lines=0)


def test_pause_holds_the_picture_and_keeps_messages() -> None:
    console = Console()
    console.add(log(20, 'a', 'before'))
    assert console.toggle_pause() is True
    version = console.version
    console.add(log(30, 'a', 'during'))
    assert console.version == version  # nothing to redraw while paused
    assert [r.message for r in console.shown()[0]] == ['before']
    assert 'PAUSED' in console.status(1, 2)
    assert console.toggle_pause() is False
    assert [r.message for r in console.shown()[0]] == ['before', 'during']


def test_columns_fit_the_width() -> None:
    console = Console()
    console.add(log(50, '/very/long/namespace/and/node_name', 'm' * 200))
    rows, _ = console.shown()
    wide = widths(rows, 160)
    assert len(line(cells(rows[0]), wide)) == 160
    assert wide[-1] > 0  # room for the location
    narrow = widths(rows, 70)
    text = line(cells(rows[0]), narrow)
    assert len(text) == 70 and text.endswith('…') and 'talker.py' not in text
    assert Filters().accepts(rows[0])
