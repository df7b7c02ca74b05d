"""`rqt_plot /turtle1/pose/x` while the turtle drives: the window under a virtual X display
(two screenshots, the line moved), the terminal plot in tmux (keys), text pictures without a
display, and bad arguments."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import Any

from ros2lite.interfaces import get_interface
from ros2lite.monitor.chart import PALETTE
from ros2lite.node import Node
from tests.bundled.screenshot import Image, screenshot
from tests.bundled.tmux import TmuxPane
from tests.bundled.turtlesim.conftest import start_turtlesim
from tests.spinning import wait_until

PLOT = [sys.executable, '-m', 'ros2lite', 'run', 'rqt_plot', 'rqt_plot']
Twist = get_interface('geometry_msgs/msg/Twist')


def no_display() -> dict[str, str]:
    return {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}


class Teleop:
    """What a teleop does: Twists on /turtle1/cmd_vel, from a node of the test's context."""

    def __init__(self, ctx: Any) -> None:
        self.node = Node('teleop_stand_in', context=ctx, enable_rosout=False)
        self.pub = self.node.create_publisher(Twist, '/turtle1/cmd_vel', 10)

    def drive(self, forward: float, turn: float) -> None:
        twist = Twist()
        twist.linear.x, twist.angular.z = forward, turn
        self.pub.publish(twist)

    def close(self) -> None:
        self.node.destroy_node()


def line_pixels(shot: Image) -> list[tuple[int, int]]:
    """Where the first series' colour is on the screen."""
    want = bytes(PALETTE[0])
    rgb, width = shot.rgb, shot.width
    return [
        (i // 3 % width, i // 3 // width) for i in range(0, len(rgb), 3) if rgb[i : i + 3] == want
    ]


def test_the_window_line_follows_the_turtle(
    ros_context: Any, processes: Any, xdisplay: str, tmp_path: Path
) -> None:
    start_turtlesim(processes, '--display', 'none')
    proc = processes.start([*PLOT, '/turtle1/pose/x'], env={**os.environ, 'DISPLAY': xdisplay})
    teleop = Teleop(ros_context)
    try:
        # the window is up and the line drawn (the legend's swatch alone is ~60 pixels)
        first = wait_until(lambda: len(line_pixels(s := screenshot(xdisplay))) > 400 and s, 30)
        first.save_png(str(tmp_path / 'before.png'))  # to look at
        before = line_pixels(first)
        # drive forward: x grows, so the right end of the line climbs
        teleop.drive(2.0, 0.0)

        def moved() -> Image | None:
            teleop.drive(2.0, 0.0)
            shot = screenshot(xdisplay)
            return shot if set(line_pixels(shot)) - set(before) and rightmost_rise(shot) else None

        def rightmost_rise(shot: Image) -> bool:
            # the newest samples (the line's right end) are above where it started (left end)
            pixels = [p for p in line_pixels(shot) if p[1] > 100]  # below the legend
            if not pixels:
                return False
            left = min(pixels)
            right = max(pixels)
            return right[0] - left[0] > 50 and right[1] < left[1] - 40

        second = wait_until(moved, 30, interval=0.2)
        second.save_png(str(tmp_path / 'after.png'))
        assert proc.poll() is None
    finally:
        teleop.close()
    processes.stop(proc)
    assert proc.returncode == 0


def test_the_terminal_plot_in_tmux(ros_context: Any, processes: Any, tmp_path: Path) -> None:
    start_turtlesim(processes, '--display', 'none')
    pane = TmuxPane([*PLOT, '/turtle1/pose/x:y'], no_display(), tmp_path, cols=120, rows=30)
    teleop = Teleop(ros_context)
    try:
        screen = pane.wait_for('/turtle1/pose/y = ')
        assert '/turtle1/pose/x = ' in screen and 'p pause' in screen
        colours = pane.screen(colours=True)
        for r, g, b in PALETTE[:2]:
            assert f'38;2;{r};{g};{b}m' in colours

        def x_shown() -> float:
            return float(pane.screen().split('/turtle1/pose/x = ')[1].split()[0])

        start = x_shown()
        wait_until(lambda: (teleop.drive(2.0, 0.0), x_shown() > start + 0.5)[1], 20)
        pane.keys('p')
        paused = pane.wait_for('PAUSED')
        held = paused.split('\n')[0]
        teleop.drive(2.0, 0.0)
        wait_until(lambda: 'PAUSED' in pane.screen(), 5)
        assert pane.screen().split('\n')[0] == held  # the picture holds while paused
        pane.keys('+')
        pane.wait_for('window 20 s')
        pane.keys('a')
        pane.wait_for('autoscale off')
        pane.keys('q')
        assert pane.exit_status() == 0
        assert 'Traceback' not in pane.history()
    finally:
        teleop.close()
        pane.close()


def test_text_pictures_without_a_display(processes: Any) -> None:
    start_turtlesim(processes, '--display', 'none')
    proc = processes.start([*PLOT, '/turtle1/pose/theta', '--display', 'none'], env=no_display())
    assert proc.stdout is not None
    head = proc.stdout.readline()
    while '/turtle1/pose/theta' not in head:
        head = proc.stdout.readline()
    assert '/turtle1/pose/theta = ' in head and 'Hz' in head
    picture = [proc.stdout.readline() for _ in range(19)]  # the rest of that picture
    assert any(0x2800 < ord(ch) <= 0x28FF for ch in ''.join(picture)), picture
    assert picture[-1].rstrip().endswith('time (s)')
    _, err = processes.stop(proc)
    assert proc.returncode == 0 and 'Traceback' not in err


def test_a_series_added_while_it_runs(ros_context: Any) -> None:
    """What the window's topic box does: a series named while the plot runs is subscribed
    and plotted; a name that cannot be is one line for the status bar."""
    import uuid

    from ros2lite.bundled.rqt_plot.rqt_plot import Session
    from ros2lite.monitor.plot import Plot

    topic = f'/level_{uuid.uuid4().hex[:8]}'
    Float64 = get_interface('std_msgs/msg/Float64')
    talker = Node('level_talker', context=ros_context, enable_rosout=False)
    plotter = Node('level_plotter', context=ros_context, enable_rosout=False)
    try:
        pub = talker.create_publisher(Float64, topic, 10)
        session = Session(plotter, Plot([], window=10.0))
        session.start()  # nothing to plot yet
        wait_until(lambda: topic in [n for n, _ in plotter.get_topic_names_and_types()], 20)
        assert session.add(f'{topic}/date') == (
            f"'{topic}/date': 'Float64' has no field 'date' (its fields: data)"
        )
        assert session.add('/no_such_topic/x') == "no topic in the graph matches '/no_such_topic/x'"
        assert session.add(f'{topic}/data') is None
        assert session.add(f'{topic}/data') is None  # twice is once
        assert [s.label for s in session.plot.series] == [f'{topic}/data']
        wait_until(lambda: pub.get_subscription_count() >= 1, 20)

        def plotted() -> bool:
            pub.publish(Float64(data=42.5))
            return session.plot.series[0].last() == 42.5

        wait_until(plotted, 20)
    finally:
        plotter.destroy_node()
        talker.destroy_node()


def test_bad_arguments() -> None:
    done = subprocess.run([*PLOT, '--display', 'none'], capture_output=True, text=True)
    assert done.returncode == 2 and 'only a window has a box to add it in' in done.stderr
    done = subprocess.run(
        [*PLOT, '/turtle1/pose/x[', '--display', 'none'], capture_output=True, text=True
    )
    assert done.returncode == 1 and 'is not a field path' in done.stderr
    assert 'Traceback' not in done.stderr
    done = subprocess.run([*PLOT, '/a/x', '--time-window', '0'], capture_output=True, text=True)
    assert done.returncode == 2 and "'0' is not a number of seconds" in done.stderr


def test_bag_plot_in_rqt_plots_window(processes: Any, xdisplay: str, tmp_path: Path) -> None:
    """`bag plot --display window`: the whole bag in the same window, both series' colours."""
    from ros2lite.bag import Writer

    Point = get_interface('geometry_msgs/msg/Point')
    with Writer(str(tmp_path / 'arc')) as bag:
        for i in range(200):
            bag.write(
                '/arc', Point(x=i / 20, y=(i / 20) ** 0.5), 1_700_000_000_000_000_000 + i * 10**7
            )
    proc = processes.cli(
        'bag',
        'plot',
        str(tmp_path / 'arc'),
        '/arc/x:y',
        '--display',
        'window',
        env={**os.environ, 'DISPLAY': xdisplay},
    )

    def drawn() -> Image | None:
        shot = screenshot(xdisplay)
        counts = [shot.count(c, (0, 0, shot.width, shot.height)) for c in PALETTE[:2]]
        return shot if min(counts) > 300 else None

    shot = wait_until(drawn, 30, interval=0.2)
    shot.save_png(str(tmp_path / 'bag_window.png'))
    assert proc.poll() is None  # it stays until the window is closed
    processes.stop(proc)
