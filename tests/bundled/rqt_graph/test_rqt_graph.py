"""`rqt_graph` against a live graph (turtlesim and a teleop-like publisher): the SVG and DOT
files, bad output names, the terminal picture in a pseudo-terminal and the window under a
virtual X display."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite.msgs.geometry_msgs.msg import Twist
from ros2lite.node import Node
from tests.bundled.ptyproc import PtyProcess, ros2lite_argv
from tests.bundled.screenshot import screenshot
from tests.bundled.turtlesim.conftest import start_turtlesim

RQT = [sys.executable, '-m', 'ros2lite', 'run', 'rqt_graph', 'rqt_graph']


@pytest.fixture
def lesson_graph(ros_context: Any, processes: Any) -> Iterator[None]:
    """turtlesim, and a `/teleop_turtle` publishing on /turtle1/cmd_vel."""
    start_turtlesim(processes, '--display', 'none')
    teleop = Node('teleop_turtle', context=ros_context)
    pub = teleop.create_publisher(Twist, 'turtle1/cmd_vel', 1)
    deadline = time.monotonic() + 10
    while pub.get_subscription_count() < 1:
        assert time.monotonic() < deadline
        time.sleep(0.05)
    # every edge the tests look for is in the graph as a tool (a client of the router, as
    # rqt_graph is) sees it, before any of them looks
    from ros2lite.graph import EntityKind
    from ros2lite.tools.connection import Connection

    def edges() -> set[tuple[str, str]]:
        with Connection(autostart=False) as conn:
            return {
                (e.node_fqn, e.topic_name or '')
                for e in conn.entities()
                if e.kind == EntityKind.PUBLISHER
            }

    wanted = {('/teleop_turtle', '/turtle1/cmd_vel'), ('/turtlesim', '/turtle1/pose')}
    while not wanted <= edges():
        assert time.monotonic() < deadline
        time.sleep(0.1)
    yield
    teleop.destroy_node()


def test_files(lesson_graph: None, tmp_path: Any) -> None:
    svg = tmp_path / 'graph.svg'
    done = subprocess.run([*RQT, '--output', str(svg)], capture_output=True, text=True)
    assert (done.returncode, done.stdout) == (0, ''), done.stderr
    text = svg.read_text()
    assert 'data-from="/teleop_turtle" data-to="/turtle1/cmd_vel"' in text
    assert 'data-from="/turtle1/cmd_vel" data-to="/turtlesim"' in text
    assert '/turtle1/pose' not in text and '/rosout' not in text  # a leaf, a debug topic
    dot = tmp_path / 'graph.dot'
    subprocess.run([*RQT, '-o', str(dot), '--show-leaf-topics'], check=True)
    lines = dot.read_text().splitlines()
    assert '  "/turtlesim" -> "/turtle1/pose";' in lines
    assert '  "/teleop_turtle" -> "/turtle1/cmd_vel";' in lines
    assert not any('_ros2lite' in line for line in lines)  # its own node is hidden

    bad = subprocess.run([*RQT, '-o', str(tmp_path / 'graph.png')], capture_output=True, text=True)
    assert bad.returncode == 1
    assert f"cannot write '{tmp_path / 'graph.png'}': the name must end in .svg or .dot" in (
        bad.stderr
    )
    link = tmp_path / 'link.svg'
    link.symlink_to(tmp_path / 'elsewhere.svg')
    refused = subprocess.run([*RQT, '-o', str(link)], capture_output=True, text=True)
    assert refused.returncode == 1 and 'Traceback' not in refused.stderr
    assert not (tmp_path / 'elsewhere.svg').exists()  # never written through a symlink


def test_terminal(lesson_graph: None) -> None:
    env = {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}
    proc = PtyProcess(ros2lite_argv('run', 'rqt_graph', 'rqt_graph'), env, rows=20, cols=100)
    try:
        proc.expect(r'rqt_graph  2 nodes, 1 topics')
        proc.expect('/teleop_turtle │───▶│ /turtle1/cmd_vel │───▶│ /turtlesim', plain=True)
        proc.send('\x03')
        assert proc.wait() == 0 and 'Traceback' not in proc.output
    finally:
        proc.close()


def test_window(lesson_graph: None, processes: Any, xdisplay: str) -> None:
    proc = processes.start([*RQT], env={**os.environ, 'DISPLAY': xdisplay})
    node_outline = (0x1F, 0x4E, 0x79)
    topic_outline = (0x7F, 0x3F, 0x00)
    deadline = time.monotonic() + 20
    while True:
        shot = screenshot(xdisplay)
        box = (0, 0, shot.width, shot.height)
        if shot.count(node_outline, box) > 50 and shot.count(topic_outline, box) > 50:
            break
        assert time.monotonic() < deadline and proc.poll() is None, proc.poll()
        time.sleep(0.3)
    processes.stop(proc)
    assert proc.returncode == 0
