"""`bag plot` of a recorded turtlesim drive: the CSV holds the recorded poses exactly, the PNG
has its curve where those poses are, the terminal gets braille, an x-y SVG; bad input is one
line."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from ros2lite.bag.reader import Reader
from ros2lite.interfaces import get_interface
from ros2lite.interfaces.convert import value_to_csv
from ros2lite.monitor.chart import PALETTE, layout, ranges
from ros2lite.monitor.plot import FieldPath, Plot, SeriesSpec, to_chart
from tests.bundled.turtlesim.conftest import start_turtlesim
from tests.monitor.test_chart import read_png
from tests.spinning import wait_until

from .conftest import subscribed

Twist = get_interface('geometry_msgs/msg/Twist')


def bag_plot(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, '-m', 'ros2lite', 'bag', 'plot', *args],
        capture_output=True,
        text=True,
        timeout=60,
    )


@pytest.fixture
def drive(processes: Any, recording: Any, node: Any, tmp_path: Path) -> Path:
    """A bag of /turtle1/pose while the turtle drives an arc (a teleop's Twists)."""
    start_turtlesim(processes, '--display', 'none')
    path = tmp_path / 'drive'
    rec = recording(path, '/turtle1/pose')
    wait_until(lambda: subscribed(node.context, '/turtle1/pose'), timeout=20)
    poses: list[Any] = []
    from ros2lite.msgs.turtlesim.msg import Pose

    node.create_subscription(Pose, '/turtle1/pose', poses.append, 10)
    pub = node.create_publisher(Twist, '/turtle1/cmd_vel', 10)
    from ros2lite.executors import SingleThreadedExecutor

    executor = SingleThreadedExecutor(context=node.context)
    executor.add_node(node)
    twist = Twist()
    twist.linear.x, twist.angular.z = 2.0, 1.0
    timer = node.create_timer(0.05, lambda: pub.publish(twist))
    # until the turtle has gone well round (its heading turned by more than 2 radians)
    executor.spin_until(lambda: bool(poses) and poses[-1].theta > 2.0, 30)
    timer.cancel()
    executor.shutdown()
    assert poses and poses[-1].theta > 2.0, 'the turtle did not drive'
    code, _, err = rec.finish()
    assert code == 0, err
    return path


def test_bag_plot_of_a_drive(drive: Path, tmp_path: Path) -> None:
    with Reader(drive) as bag:
        recorded = [(t, msg) for _, msg, t in bag.messages(['/turtle1/pose'])]
    assert len(recorded) > 20
    t0 = recorded[0][0]

    done = bag_plot(str(drive), '/turtle1/pose/x:y', '--csv')
    assert done.returncode == 0, done.stderr
    header, *rows = done.stdout.splitlines()
    assert header == 'time,/turtle1/pose/x,/turtle1/pose/y'
    assert len(rows) == len(recorded)
    for row, (t, pose) in zip(rows, recorded, strict=True):
        assert row.split(',') == [
            f'{(t - t0) * 1e-9:.6f}',
            value_to_csv(pose.x),
            value_to_csv(pose.y),
        ]

    png = tmp_path / 'drive.png'
    done = bag_plot(str(drive), '/turtle1/pose/x', '--png', str(png), '--size', '640x400')
    assert done.returncode == 0 and f'Wrote {png} ({len(recorded)} messages)' in done.stderr
    width, height, rgb = read_png(png.read_bytes())
    # where the recorded poses put the curve: the picture's own axes (its layout) mapping the
    # bag's times and x values, each spot within two pixels of the line's colour
    plot = Plot([SeriesSpec('/turtle1/pose', FieldPath.parse('x'))], window=None, live=False)
    for t, pose in recorded:
        plot.feed('/turtle1/pose', pose, t * 1e-9)
    chart = to_chart(plot)
    frame = layout(chart, width, height)
    (x0, x1), (y0, y1) = ranges(chart)
    legend_bottom = frame.top + 8 + 18 + 6
    checked = 0
    for t, pose in recorded[:: max(1, len(recorded) // 25)]:
        px = frame.left + ((t - t0) * 1e-9 - x0) / (x1 - x0) * (frame.right - frame.left)
        py = frame.bottom - (pose.x - y0) / (y1 - y0) * (frame.bottom - frame.top)
        if py < legend_bottom + 4 and px < frame.left + 300:
            continue  # under the legend box
        near = [
            tuple(rgb[((round(py) + dy) * width + round(px) + dx) * 3 :][:3])
            for dy in range(-2, 3)
            for dx in range(-2, 3)
        ]
        assert PALETTE[0] in near, (t, pose.x, px, py)
        checked += 1
    assert checked >= 10
    # and no stray curve: the line's colour only near the recorded values
    assert sum(1 for i in range(0, len(rgb), 3) if tuple(rgb[i : i + 3]) == PALETTE[0]) > 200

    done = bag_plot(str(drive), '/turtle1/pose/theta')
    assert done.returncode == 0 and '/turtle1/pose/theta = ' in done.stdout.splitlines()[0]
    assert sum(1 for ch in done.stdout if 0x2800 < ord(ch) <= 0x28FF) > 30
    assert done.stdout.splitlines()[-1].endswith('time (s)')

    done = bag_plot(str(drive), '/turtle1/pose/x,y', '--xy', '--svg', str(tmp_path / 'xy.svg'))
    assert done.returncode == 0, done.stderr
    assert '/turtle1/pose/y against x' in (tmp_path / 'xy.svg').read_text()

    # bad input, on the same bag (a drive takes seconds to record)
    done = bag_plot(str(drive), '/turtle2/pose/x')
    assert done.returncode == 1
    assert done.stderr.strip() == (
        "no topic of the bag matches '/turtle2/pose/x' (its topics: /turtle1/pose)"
    )
    done = bag_plot(str(drive), '/turtle1/pose/x', '--header-stamp')
    assert done.returncode == 1 and 'has no header' in done.stderr
    done = bag_plot(str(drive), '/turtle1/pose/name')
    assert done.returncode == 1 and "has no field 'name'" in done.stderr
    done = bag_plot(str(drive) + '_missing', '/turtle1/pose/x')
    assert done.returncode == 1 and 'does not exist' in done.stderr
    assert 'Traceback' not in done.stderr
