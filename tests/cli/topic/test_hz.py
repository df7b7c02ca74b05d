"""`topic hz` against publishers with a known rate: line format, accuracy, tables, Ctrl-C."""

from __future__ import annotations

import os
import re
from typing import Any

from ros2lite.interfaces import get_interface

from ...conftest import wait_until
from .conftest import Watch

String = get_interface('std_msgs/msg/String')
Int32 = get_interface('std_msgs/msg/Int32')
BLOCK = re.compile(
    r'average rate: (\d+\.\d{3})\n\tmin: (\d+\.\d{3})s max: (\d+\.\d{3})s '
    r'std dev: (\d+\.\d{5})s window: (\d+)\n'
)
HEADER = ['topic', 'rate', 'min_delta', 'max_delta', 'std_dev', 'window']


def test_single_topic_rate_and_format(processes: Any, talker: Any, topic: str) -> None:
    talker(topic, 'std_msgs/msg/String', lambda i: String(data=str(i)), rate=50)
    hz = Watch(processes.cli('topic', 'hz', topic))
    wait_until(lambda: len(BLOCK.findall(hz.text)) >= 2, timeout=15)
    code, err = hz.interrupt()
    assert (code, err) == (2, '')  # Ctrl-C: ros2cli's status 2
    assert BLOCK.sub('', hz.text) == ''  # nothing but the reports
    blocks = BLOCK.findall(hz.text)
    for rate, low, high, _std, _window in blocks:
        assert abs(float(rate) - 50) < 50 * 0.03, hz.text
        assert float(low) <= 0.02 <= float(high)
    windows = [int(b[4]) for b in blocks]
    assert windows == sorted(windows) and windows[0] >= 30  # one gap per message so far


def test_waits_for_topic_filters_and_window(processes: Any, talker: Any, topic: str) -> None:
    hz = Watch(processes.cli('topic', 'hz', topic, '-w', '10', '--filter', 'm.data % 2 == 0'))
    warning = f'WARNING: topic [{topic}] does not appear to be published yet\n'
    wait_until(lambda: hz.text == warning)
    talker(topic, 'std_msgs/msg/Int32', lambda i: Int32(data=i), rate=50)
    wait_until(lambda: len(BLOCK.findall(hz.text)) >= 2, timeout=15)
    code, _ = hz.interrupt()
    assert code == 2
    assert hz.text.startswith(warning)
    blocks = BLOCK.findall(hz.text[len(warning) :])
    assert BLOCK.sub('', hz.text[len(warning) :]) == ''
    for rate, _low, _high, _std, window in blocks:
        # every other message passes: 25 Hz, never the talker's 50 (a window of 10 arrivals
        # can read fast when load delays a few and delivers them together)
        assert abs(float(rate) - 25) < 25 * 0.4
        assert window == '10'


def check_table(text: str, topics: list[str]) -> list[dict[str, str]]:
    """Parse the tables hz prints and check each is laid out exactly as ros2cli's."""
    rows_seen = []
    for table in text.split('\n\n'):
        if not table.strip():
            continue
        lines = table.split('\n')
        cells = [line.split() for line in lines[2:]]
        widths = [max(len(h), *(len(r[i]) for r in cells)) for i, h in enumerate(HEADER)]
        assert lines[0] == '   '.join(h.center(w) for h, w in zip(HEADER, widths, strict=True))
        assert lines[1] == '=' * (sum(widths) + 3 * (len(HEADER) - 1))
        for line, row in zip(lines[2:], cells, strict=True):
            assert line == '   '.join(c.ljust(w) for c, w in zip(row, widths, strict=True))
            assert row[0] in topics
            rows_seen.append(dict(zip(HEADER, row, strict=True)))
    return rows_seen


def test_several_topics_print_a_table(processes: Any, talker: Any, topic: str) -> None:
    fast, slow = topic + '_fast', topic + '_slow'
    talker(fast, 'std_msgs/msg/String', lambda i: String(data='f'), rate=50)
    talker(slow, 'std_msgs/msg/String', lambda i: String(data='s'), rate=20, node_name='slow')
    hz = Watch(processes.cli('topic', 'hz', fast, slow))
    wait_until(lambda: hz.text.count('=\n') >= 2, timeout=15)
    code, _ = hz.interrupt()
    assert code == 2
    head = f'Subscribed to [{fast}]\nSubscribed to [{slow}]\n'
    assert hz.text.startswith(head)
    body = hz.text[len(head) :]
    complete = body[: body.rindex('\n\n') + 2]  # drop a table cut by Ctrl-C
    rows = check_table(complete, [fast, slow])
    rates = {r['topic']: float(r['rate']) for r in rows}
    assert abs(rates[fast] - 50) < 1.5 and abs(rates[slow] - 20) < 0.6
    assert all(re.fullmatch(r'\d+\.\d{5}', r['std_dev']) for r in rows)


def test_table_on_a_terminal(processes: Any, talker: Any, topic: str) -> None:
    import pty
    import select
    import subprocess
    import sys
    import time

    fast, slow = topic + '_a', topic + '_b'
    talker(fast, 'std_msgs/msg/String', lambda i: String(data='a'), rate=50)
    talker(slow, 'std_msgs/msg/String', lambda i: String(data='b'), rate=20, node_name='b')
    leader, follower = pty.openpty()
    env = {k: v for k, v in os.environ.items() if k != 'NO_COLOR'}
    proc = processes.start(
        [sys.executable, '-m', 'ros2lite', 'topic', 'hz', fast, slow],
        stdout=follower,
        stderr=subprocess.PIPE,
        env=env,
    )
    os.close(follower)
    seen = b''
    deadline = time.monotonic() + 15
    while time.monotonic() < deadline and b'min_delta' not in seen:
        if select.select([leader], [], [], 0.2)[0]:
            seen += os.read(leader, 65536)
    _, err = processes.stop(proc)
    os.close(leader)
    assert b'min_delta' in seen, seen
    assert fast.encode() in seen and proc.returncode == 2, err
    assert '━'.encode() in seen and b'=====' not in seen  # rich's table, not the ASCII one


def test_help_says_what_ros2cli_says() -> None:
    from click.testing import CliRunner

    from ros2lite.cli.main import cli

    runner = CliRunner()
    page = runner.invoke(cli, ['topic', 'hz', '--help']).output
    assert page.splitlines()[2] == '  Print the average publishing rate to screen'
    listing = runner.invoke(cli, ['topic', '--help']).output
    assert '  hz     Print the average publishing rate to screen\n' in listing
