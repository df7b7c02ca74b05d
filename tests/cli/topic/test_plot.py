"""`topic plot` against live publishers: CSV equal to `topic echo --csv`, PNG/SVG pictures with
the series' colour, a LaserScan profile (--snapshot, sensor-data QoS), an x-y path, the live
terminal plot in tmux, and bad input as one line."""

from __future__ import annotations

import math
import os
import shutil
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from ros2lite.interfaces import get_interface
from ros2lite.monitor.chart import PALETTE
from ros2lite.node import Node
from ros2lite.qos import QoSProfile, qos_profile_sensor_data
from tests.bundled.tmux import TmuxPane

from ...conftest import wait_until
from ..conftest import Result
from .conftest import Watch

Float64 = get_interface('std_msgs/msg/Float64')
Point = get_interface('geometry_msgs/msg/Point')
LaserScan = get_interface('sensor_msgs/msg/LaserScan')
Odometry = get_interface('nav_msgs/msg/Odometry')
LIMIT = ('--duration', '20')  # safety net: a broken plot fails instead of hanging


def braille_cells(text: str) -> int:
    return sum(1 for ch in text if 0x2800 < ord(ch) <= 0x28FF)


def read_ppm(data: bytes) -> tuple[int, int, bytes]:
    """(width, height, RGB) of a binary PPM (what `convert FILE.png ppm:-` prints)."""
    fields: list[bytes] = []
    pos = 0
    while len(fields) < 4:
        while data[pos : pos + 1].isspace():
            pos += 1
        end = pos
        while not data[end : end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    assert fields[0] == b'P6' and fields[3] == b'255'
    width, height = int(fields[1]), int(fields[2])
    return width, height, data[pos + 1 : pos + 1 + width * height * 3]


def pixels_of(rgb: bytes, colour: tuple[int, int, int]) -> int:
    want = bytes(colour)
    return sum(1 for i in range(0, len(rgb), 3) if rgb[i : i + 3] == want)


def test_csv_equals_what_topic_echo_csv_prints(
    ros_context: Any, processes: Any, topic: str
) -> None:
    reliable = ('--qos-reliability', 'reliable', '--qos-depth', '100')
    plot = Watch(
        processes.cli(
            'topic', 'plot', f'{topic}/x:y:z', '--csv', '--count', '20', *reliable, *LIMIT
        )
    )
    echo = Watch(
        processes.cli('topic', 'echo', topic, 'geometry_msgs/msg/Point', '--csv', *reliable)
    )
    node = Node('points', context=ros_context, enable_rosout=False)
    try:
        pub = node.create_publisher(Point, topic, QoSProfile(depth=100))
        wait_until(lambda: pub.get_subscription_count() >= 2, timeout=20)
        for i in range(20):
            pub.publish(Point(x=i / 3, y=-i * 1.25, z=math.pi * i))
        wait_until(lambda: len(echo.lines) >= 20 and plot.proc.poll() is not None, timeout=20)
    finally:
        node.destroy_node()
    assert plot.proc.returncode == 0, plot.proc.stderr.read()
    echo.interrupt()
    header, *rows = plot.text.splitlines()
    assert header == f'time,{topic}/x,{topic}/y,{topic}/z'
    assert len(rows) == 20
    plotted = [row.split(',', 1)[1] for row in rows]
    assert plotted == [line.rstrip('\n') for line in echo.lines[:20]]
    times = [float(row.split(',')[0]) for row in rows]
    assert times[0] == 0.0 and times == sorted(times)


def test_png_and_svg_pictures(
    run: Callable[..., Result], talker: Any, topic: str, tmp_path: Path
) -> None:
    talker(topic, 'std_msgs/msg/Float64', lambda i: Float64(data=math.sin(i / 10)))
    png, svg = tmp_path / 'plot.png', tmp_path / 'plot.svg'
    result = run(
        'topic',
        'plot',
        f'{topic}/data',
        '--count',
        '40',
        '--png',
        str(png),
        '--svg',
        str(svg),
        '--size',
        '640x400',
        *LIMIT,
    )
    assert result.code == 0, result.err
    assert f'Wrote {png} (40 messages)' in result.err and result.out == ''
    assert png.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'
    text = svg.read_text()
    assert text.startswith('<svg') and f'>{topic}/data' in text and 'stroke="#1f77b4"' in text
    convert = shutil.which('convert')
    if convert is None:
        pytest.skip('no ImageMagick convert to read the PNG with')
    ppm = subprocess.run([convert, str(png), 'ppm:-'], capture_output=True, check=True).stdout
    width, height, rgb = read_ppm(ppm)
    assert (width, height) == (640, 400)
    assert pixels_of(rgb, PALETTE[0]) > 300  # the line, in the first series' colour


def test_snapshot_of_a_laser_scan(
    run: Callable[..., Result], talker: Any, topic: str, tmp_path: Path
) -> None:
    # a sensor-data publisher (best effort): rqt_plot's own never hears one (rqt_plot#40)
    def scan(i: int) -> Any:
        return LaserScan(ranges=[1.0 + math.sin(k / 20) for k in range(360)], range_max=10.0)

    talker(topic, 'sensor_msgs/msg/LaserScan', scan, qos=qos_profile_sensor_data)
    result = run('topic', 'plot', f'{topic}/ranges', '--snapshot', '--count', '3', *LIMIT)
    assert result.code == 0, result.err
    lines = result.out.splitlines()
    assert f'{topic}/ranges = ' in lines[0] and lines[-1].endswith('index')
    assert braille_cells(result.out) > 60
    assert '360' not in lines[-1] and '300' in lines[-1]  # the indices 0..359 on x
    png = tmp_path / 'scan.png'
    result = run('topic', 'plot', f'{topic}/ranges', '--snapshot', '--png', str(png), *LIMIT)
    assert result.code == 0 and '(1 messages)' in result.err, result.err
    result = run('topic', 'plot', f'{topic}/ranges[10]', '--snapshot', '--count', '1', *LIMIT)
    assert result.code == 1 and 'is one number; --snapshot plots arrays' in result.err


def test_xy_of_odometry(run: Callable[..., Result], talker: Any, topic: str) -> None:
    def odom(i: int) -> Any:
        msg = Odometry()
        msg.pose.pose.position.x = 3 * math.cos(i / 5)
        msg.pose.pose.position.y = 3 * math.sin(i / 5)
        return msg

    talker(topic, 'nav_msgs/msg/Odometry', odom)
    result = run(
        'topic', 'plot', '--xy', f'{topic}/pose/pose/position/x,y', '--count', '40', *LIMIT
    )
    assert result.code == 0, result.err
    lines = result.out.splitlines()
    assert f'{topic}/pose/pose/position/y against pose/pose/position/x' in lines[0]
    assert lines[-1].endswith('pose/pose/position/x')
    assert braille_cells(result.out) > 40
    assert '-2' in lines[-1] and '2' in lines[-1]  # a circle of radius 3 about 0


def test_the_terminal_plot_draws_and_updates_in_tmux(
    talker: Any, topic: str, tmp_path: Path
) -> None:
    talker(topic, 'std_msgs/msg/Float64', lambda i: Float64(data=float(i)), rate=20)
    pane = TmuxPane(
        [sys.executable, '-m', 'ros2lite', 'topic', 'plot', f'{topic}/data', '--time-window', '5'],
        dict(os.environ),
        tmp_path,
        cols=100,
        rows=24,
    )
    try:
        first = pane.wait_for(f'{topic}/data = ')
        wait_until(lambda: braille_cells(pane.screen()) > 20, timeout=20)
        coloured = pane.screen(colours=True)
        r, g, b = PALETTE[0]
        assert f'38;2;{r};{g};{b}m' in coloured
        value = lambda s: float(s.split(f'{topic}/data = ')[1].split()[0])  # noqa: E731
        before = value(pane.screen())
        later = wait_until(lambda: value(s := pane.screen()) >= before + 10 and s, timeout=20)
        assert later != first and '┤' in later and 'time (s)' in later
        assert 'Hz' in later.splitlines()[0]
        pane.keys('C-c')
        assert pane.exit_status() in (0, 2, 130)
        # the alternate screen is left; the last picture stays on the normal one (its first
        # line scrolled up by the line tmux adds for the dead pane)
        final = pane.history()
        assert f'{topic}/data = ' in final and 'Traceback' not in final
    finally:
        pane.close()


def test_bad_input_is_one_line(run: Callable[..., Result], talker: Any, topic: str) -> None:
    talker(topic, 'std_msgs/msg/Float64', lambda i: Float64(data=1.0))
    result = run('topic', 'plot', f'{topic}/date', *LIMIT)
    assert result.code == 1
    assert result.err.strip().splitlines()[-1] == (
        f"'{topic}/date': 'Float64' has no field 'date' (its fields: data)"
    )
    result = run('topic', 'plot', '--xy', f'{topic}/data', *LIMIT)
    assert result.code == 1 and 'takes two values of one topic' in result.err
    result = run('topic', 'plot', '--xy', '--snapshot', f'{topic}/data')
    assert result.code == 1 and 'choose one' in result.err
    result = run('topic', 'plot', f'{topic}/data[', '--duration', '1')
    assert result.code == 1 and 'is not a field path' in result.err
    result = run(
        'topic', 'plot', f'{topic}/data', '--png', '/nonexistent/dir/x.png', '--count', '1', *LIMIT
    )
    assert result.code == 1 and "cannot write '/nonexistent/dir/x.png'" in result.err
    assert 'Traceback' not in result.err
    started = time.monotonic()
    result = run('topic', 'plot', f'{topic}/data', '--png', 'x.jpg', '--count', '1', *LIMIT)
    assert result.code == 1 and 'a picture is written as .png or .svg' in result.err
    assert time.monotonic() - started < 20
