"""joint_state_publisher_gui under a virtual X display, as a person uses it: the window shows
a slider per free joint (checked on a screenshot), and a click on the elbow's slider (X events
from xdotool) changes the elbow's position on /joint_states."""

from __future__ import annotations

import os
import shutil
import subprocess
import time
from pathlib import Path
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.msgs.sensor_msgs.msg import JointState
from ros2lite.node import Node
from tests.bundled.screenshot import Image, screenshot
from tests.spinning import spin_until
from tests.urdf.robots import ARM

BACKGROUND = (217, 217, 217)  # Tk's default window colour on X11
TROUGH = (179, 179, 179)  # a Tk scale's trough


def troughs(shot: Image) -> list[tuple[int, int, int]]:
    """(middle row, left, right) of each slider's trough, top to bottom: the bands of rows
    that hold a long run of the trough colour."""
    rows = []
    for y in range(shot.height):
        xs = [x for x in range(shot.width) if shot.pixel(x, y) == TROUGH]
        if len(xs) > 100:
            rows.append((y, xs[0], xs[-1]))
    bands: list[list[tuple[int, int, int]]] = []
    for row in rows:
        if bands and row[0] == bands[-1][-1][0] + 1:
            bands[-1].append(row)
        else:
            bands.append([row])
    return [band[len(band) // 2] for band in bands]


def knob(shot: Image, y: int, left: int, right: int) -> float:
    """Where along the trough (0..1) the slider's knob is: the middle of the run of non-trough
    pixels inside it."""
    inside = [x for x in range(left, right + 1) if shot.pixel(x, y) != TROUGH]
    return ((inside[0] + inside[-1]) / 2 - left) / (right - left)


def test_a_slider_moves_its_joint(
    processes: Any, ros_context: Any, xdisplay: str, tmp_path: Path
) -> None:
    if shutil.which('xdotool') is None:
        pytest.skip(
            'xdotool is not installed: the test clicks the slider (apt-get install xdotool)'
        )
    urdf = tmp_path / 'arm.urdf'
    urdf.write_text(ARM)
    env = {**os.environ, 'DISPLAY': xdisplay}
    gui = processes.cli(
        'run', 'joint_state_publisher_gui', 'joint_state_publisher_gui', str(urdf), env=env
    )
    node = Node('gui_probe', context=ros_context)
    states: list[JointState] = []
    node.create_subscription(JointState, '/joint_states', states.append, 10)
    executor = SingleThreadedExecutor(context=node.context)
    executor.add_node(node)
    try:
        spin_until(executor, lambda: states, timeout=30)
        assert dict(zip(states[-1].name, states[-1].position, strict=True))['elbow'] == 0.0
        deadline = time.monotonic() + 15
        while len(found := troughs(shot := screenshot(xdisplay))) < 4:
            assert time.monotonic() < deadline, 'the window never showed its four sliders'
            time.sleep(0.2)
        shot.save_png(str(tmp_path / 'joint_state_publisher_gui.png'))
        # four free joints (elbow, slide, finger_left_joint, wheel_joint; the mimic one has none)
        assert len(found) == 4
        assert shot.count(BACKGROUND, (0, 0, 300, 200)) > 20_000  # a window, not a black screen
        y, left, right = found[0]  # the elbow's, first in the description
        assert knob(shot, y, left, right) == pytest.approx(0.5, abs=0.05)  # 0 in [-1.5, 1.5]
        # Tk's scale jumps to where the middle button clicks
        x = left + int(0.9 * (right - left))
        subprocess.run(
            ['xdotool', 'mousemove', str(x), str(y), 'click', '2'], env=env, check=True, timeout=10
        )

        def elbow() -> float:
            return dict(zip(states[-1].name, states[-1].position, strict=True))['elbow']

        spin_until(executor, lambda: elbow() > 0.8, timeout=10)
        assert elbow() <= 1.5
        moved = screenshot(xdisplay)
        moved.save_png(str(tmp_path / 'joint_state_publisher_gui_moved.png'))
        assert knob(moved, y, left, right) > 0.8
    finally:
        executor.shutdown()
        node.destroy_node()
    _, err = processes.stop(gui)
    assert 'Traceback' not in err
