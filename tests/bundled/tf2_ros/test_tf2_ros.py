"""tf2_ros's tools: static_transform_publisher's two command-line forms, tf2_echo's printout
(the real tool's layout, for a transform worked out independently), a static transform that
reaches a tf2_echo started after it (transient local), bad command lines, and tf2_monitor's
report."""

from __future__ import annotations

import queue
import re
import subprocess
import sys
import threading
import time
from typing import Any

import pytest

from ros2lite.bundled.tf2_ros.static_transform_publisher import UsageError, parse
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.msgs.tf2_msgs.msg import TFMessage

# x y z = 1 2 3, roll pitch yaw = 0.1 0.2 0.3, as tf2_echo prints it (quaternion and matrix
# from transforms3d's euler2quat/quat2mat with static xyz axes)
ECHO = """\
At time 0.0
- Translation: [1.000, 2.000, 3.000]
- Rotation: in Quaternion [0.034, 0.106, 0.144, 0.983]
- Rotation: in RPY (radian) [0.100, 0.200, 0.300]
- Rotation: in RPY (degree) [5.730, 11.459, 17.189]
- Matrix:
  0.936 -0.275  0.218  1.000
  0.290  0.956 -0.037  2.000
 -0.199  0.098  0.975  3.000
  0.000  0.000  0.000  1.000
"""

NEW_STYLE = [
    '--x', '1', '--y', '2', '--z', '3', '--roll', '0.1', '--pitch', '0.2', '--yaw', '0.3',
    '--frame-id', 'world', '--child-frame-id', 'robot',
]  # fmt: skip


def run_tool(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, '-m', 'ros2lite', 'run', 'tf2_ros', *args],
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def test_both_command_line_forms_mean_the_same_transform() -> None:
    new = parse(NEW_STYLE)
    old = parse(['1', '2', '3', '0.3', '0.2', '0.1', 'world', 'robot'])  # yaw pitch roll
    assert (new.translation, new.frame_id, new.child_frame_id) == (
        (1.0, 2.0, 3.0),
        'world',
        'robot',
    )
    assert new.rotation == old.rotation and old.old_style and not new.old_style
    quat = parse(['0', '0', '0', '0', '0', '0.6', '0.8', 'a', 'b'])
    assert quat.rotation == (0.0, 0.0, 0.6, 0.8)
    assert parse(['--frame-id', 'a', '--child-frame-id', 'b']).rotation == (0.0, 0.0, 0.0, 1.0)
    for bad, why in [
        (['--qx', '1', '--roll', '1', '--frame-id', 'a', '--child-frame-id', 'b'], 'both'),
        (['--x', 'one', '--frame-id', 'a', '--child-frame-id', 'b'], 'Failed to parse --x'),
        (['--child-frame-id', 'b'], 'Frame id must not be empty'),
        (['--frame-id'], 'Not enough arguments for --frame-id'),
        (['1', '2', '--frame-id', 'a', '--child-frame-id', 'b'], 'Extra unparsed'),
        (['--x', '1', '0', '0', '0', '0', '0', '0', 'a', 'b'], r'new-style \(flags\) and old'),
    ]:
        with pytest.raises(UsageError, match=why):
            parse(bad)


def test_bad_command_lines_say_why() -> None:
    bad = run_tool('static_transform_publisher', '--x', 'one')
    assert bad.returncode == 1
    errors = [line for line in bad.stderr.splitlines() if not line.startswith('[ros2run]')]
    assert len(errors) == 1 and errors[0].endswith(
        'error parsing command line arguments: Failed to parse --x argument as float'
    ), bad.stderr
    assert bad.stdout.startswith('usage: static_transform_publisher [--x X]')
    echo = run_tool('tf2_echo', 'world')
    assert echo.returncode == 1
    assert echo.stdout.startswith('Usage: tf2_echo source_frame target_frame [echo_rate]\n')
    for rate, code in (('fast', 2), ('1.0foo', 3)):
        got = run_tool('tf2_echo', 'a', 'b', rate)
        assert got.returncode == code
        assert f"Failed to convert rate argument '{rate}' to a floating-point number" in got.stderr
        assert 'Traceback' not in got.stderr


def test_publisher_logs_as_tf2_ros_does(capfd: Any) -> None:
    """tf2_ros's program logs through rcutils' unnamed logger (`[]`), and warns of the old
    style as soon as it sees it, before finding the command line wrong."""
    from ros2lite.bundled.tf2_ros.static_transform_publisher import main

    assert main(['--x', '1', '0', '0', '0', '0', '0', '0', 'a', 'b']) == 1
    err = capfd.readouterr().err.splitlines()
    assert len(err) == 2, err
    assert re.fullmatch(
        r'\[WARN\] \[\d+\.\d+\] \[\]: Old-style arguments are deprecated; see --help for '
        r'new-style arguments',
        err[0],
    ), err
    assert re.fullmatch(
        r'\[ERROR\] \[\d+\.\d+\] \[\]: error parsing command line arguments: Cannot specify '
        r'both new-style \(flags\) and old-style \(arguments\)',
        err[1],
    ), err


def _lines(proc: Any, stream: str = 'stdout') -> queue.Queue[str | None]:
    """The lines of the process's stdout or stderr, read by a thread (None once it ends), so
    that waiting for them can time out."""
    lines: queue.Queue[str | None] | None = getattr(proc, f'{stream}_lines', None)
    if lines is None:
        lines = queue.Queue()
        setattr(proc, f'{stream}_lines', lines)
        source = getattr(proc, stream)

        def pump() -> None:
            for line in source:
                lines.put(line)
            lines.put(None)

        threading.Thread(target=pump, daemon=True).start()
    return lines


def _next_line(proc: Any, stream: str, deadline: float, seen: str) -> str:
    """The next line of the stream, failing the test at the deadline or when it ends."""
    try:
        line = _lines(proc, stream).get(timeout=max(0.0, deadline - time.monotonic()))
    except queue.Empty:
        raise AssertionError(f'no line in time on {stream} after:\n{seen}') from None
    assert line is not None, f'{seen}\n(the process ended)'
    return line


def read_until(proc: Any, text: str, timeout: float = 30) -> str:
    """stdout of `proc` up to and including the first line that completes `text`."""
    seen = ''
    deadline = time.monotonic() + timeout
    while not seen.endswith(text):
        seen += _next_line(proc, 'stdout', deadline, seen)
    return seen


def stderr_until(proc: Any, text: str, timeout: float = 30) -> str:
    """The first line of the process's stderr that contains `text`."""
    seen = ''
    deadline = time.monotonic() + timeout
    while text not in (line := _next_line(proc, 'stderr', deadline, seen)):
        seen += line
    return line


def stderr_lines(proc: Any, count: int, timeout: float = 30) -> list[str]:
    """The next `count` lines of the process's stderr, without their line ends."""
    deadline = time.monotonic() + timeout
    return [_next_line(proc, 'stderr', deadline, '').rstrip('\n') for _ in range(count)]


def test_static_transform_reaches_a_later_tf2_echo(processes: Any) -> None:
    publisher = processes.cli('run', 'tf2_ros', 'static_transform_publisher', *NEW_STYLE)
    stderr_until(publisher, 'Spinning until stopped - publishing transform')
    lines = stderr_lines(publisher, 3)
    assert lines == [
        "translation: ('1.000000', '2.000000', '3.000000')",
        "rotation: ('0.034271', '0.106021', '0.143572', '0.983347')",
        "from 'world' to 'robot'",
    ]
    # started after the one message was sent: only transient local brings it
    echo = processes.cli('run', 'tf2_ros', 'tf2_echo', 'world', 'robot', '5')
    first = read_until(echo, '  0.000  0.000  0.000  1.000\n')
    assert first.endswith(ECHO), first
    # the transform the other way round is the inverse
    assert read_until(echo, '1.000\n').startswith('At time 0.0\n')
    processes.stop(echo)
    inverse = processes.cli('run', 'tf2_ros', 'tf2_echo', 'robot', 'world')
    block = read_until(inverse, '  0.000  0.000  0.000  1.000\n')
    assert '- Rotation: in Quaternion [-0.034, -0.106, -0.144, 0.983]\n' in block
    processes.stop(inverse)
    old = processes.cli(
        'run', 'tf2_ros', 'static_transform_publisher', '0', '0', '1', '0', '0', '0', 'robot',
        'camera',
    )  # fmt: skip
    stderr_until(old, 'Old-style arguments are deprecated; see --help for new-style arguments')
    chained = processes.cli('run', 'tf2_ros', 'tf2_echo', 'world', 'camera')
    block = read_until(chained, '  0.000  0.000  0.000  1.000\n')
    assert '- Translation: [1.218, 1.963, 3.975]\n' in block  # robot's z axis, 1 m along
    processes.stop(chained)


def test_monitor_report(ros_context: Any, capsys: Any) -> None:
    from ros2lite.bundled.tf2_ros.tf2_monitor import Tf2Monitor

    monitor = Tf2Monitor(context=ros_context)
    try:
        now = monitor.get_clock().now().to_msg()
        for child, parent in (('base', 'odom'), ('odom', 'map')):
            t = TransformStamped(child_frame_id=child)
            t.header.frame_id = parent
            t.header.stamp = now
            monitor.on_message(TFMessage(transforms=[t]))
        monitor.report()
    finally:
        monitor.listener.unregister()
        monitor.destroy_node()
    out, err = capsys.readouterr()
    lines = out.splitlines()
    assert lines[:6] == ['', '', '', 'RESULTS: for all Frames', '', 'Frames:']
    assert lines[6].startswith('Frame: base, published by <no authority available>, Average ')
    assert lines[7].startswith('Frame: odom, published by <no authority available>, Average ')
    assert (
        lines[8].startswith('Node: <no authority available> ')
        and ' Hz, Average Delay: ' in lines[8]
    )
    assert err == '\nAll Broadcasters:\n'


def test_monitor_of_two_frames(ros_context: Any, capsys: Any) -> None:
    from ros2lite.bundled.tf2_ros.tf2_monitor import Tf2Monitor

    monitor = Tf2Monitor('base', 'map', context=ros_context)
    try:
        monitor.tick()  # nothing known yet: it waits, saying why
        assert not monitor.gathering
        now = monitor.get_clock().now().to_msg()  # one time: a lookup needs a shared one
        for child, parent in (('base', 'odom'), ('odom', 'map')):
            t = TransformStamped(child_frame_id=child)
            t.header.frame_id = parent
            t.header.stamp = now
            monitor.buffer.set_transform(t, 'test')
            monitor.on_message(TFMessage(transforms=[t]))
        for _ in range(21):
            monitor.tick()
    finally:
        monitor.listener.unregister()
        monitor.destroy_node()
    lines = capsys.readouterr().out.splitlines()
    assert lines[:5] == [
        'Gathering data on base -> map for 10 seconds...',
        '',
        '',
        '',
        'RESULTS: for base to map',
    ]
    assert lines[5] == 'Chain is: base -> odom -> map'
    assert lines[6].startswith('Net delay     avg = ') and ': max = ' in lines[6]
    assert [line.split(',')[0] for line in lines[9:11]] == ['Frame: base', 'Frame: odom']
    assert lines[11].startswith('Node: <no authority available> ')
