"""`ros2lite launch jackal_viz view_model.launch.py port:=N` beside the simulated Jackal
(jackal_gazebo's race world, its description from robot_state_publisher): the page serves on
that port with fixed frame odom, its panel lists the RobotModel and the front laser's
LaserScan, and a real headless Chromium shows the laser's red hits of the course's walls and
the robot's near-black body at odom's origin, the screen's centre: dark pixels there that go
when the RobotModel display is switched off (the TF display is off first, so its frame names,
dark text at the same place, are not taken for the robot)."""

from __future__ import annotations

import subprocess
import urllib.request
from pathlib import Path
from typing import Any

import pytest

from tests.bundled.rviz2.browser import Browser, chromium, count, red
from tests.conftest import Processes
from tests.spinning import free_port, wait_until

pytestmark = pytest.mark.skipif(
    chromium() is None, reason='chromium is not installed (apt-get install chromium)'
)
SHOTS = Path('/tmp') / 'jackal-viz-shots'
W, H = 900, 700
# round the screen's centre, where the camera looks at odom's origin (the robot, 0.6 m
# across, is some 30 px there), clear of the panel (right) and the notice (top left)
MIDDLE = (W // 2 - 80, H // 2 - 80, W // 2 + 80, H // 2 + 80)
ROBOT = 'RobotModel /robot_description'


def body(r: int, g: int, b: int) -> bool:
    """The Jackal's near-black body (its URDF's 0.1 0.1 0.1, lit and shaded)."""
    return max(r, g, b) < 80 and max(r, g, b) - min(r, g, b) < 25


def _serving(port: int) -> bool:
    try:
        with urllib.request.urlopen(f'http://127.0.0.1:{port}/', timeout=2) as reply:
            return reply.status == 200 and b'<html' in reply.read().lower()
    except OSError:
        return False


def _switch_off(browser: Browser, label: str) -> None:
    """A mouse click on the display's checkbox, once the panel shows it."""
    where = wait_until(lambda: browser.checkbox_centre(label), timeout=60, interval=0.5)
    browser.click(*where)


@pytest.mark.timeout(300)
def test_view_model_serves_the_jackal_on_the_port_given(
    processes: Processes, tmp_path: Path
) -> None:
    sim_log, viz_log = tmp_path / 'sim.log', tmp_path / 'viz.log'
    with sim_log.open('w') as sim_out, viz_log.open('w') as viz_out:
        processes.cli(
            'launch', 'jackal_gazebo', 'jackal_world.launch.py', 'headless:=true',
            stdout=sim_out, stderr=subprocess.STDOUT,
        )  # fmt: skip
        port = free_port()
        viz = processes.cli(
            'launch', 'jackal_viz', 'view_model.launch.py', f'port:={port}',
            stdout=viz_out, stderr=subprocess.STDOUT,
        )  # fmt: skip
    wait_until(lambda: _serving(port) or viz.poll() is not None, timeout=60)
    assert viz.poll() is None, viz_log.read_text()
    url = f'http://127.0.0.1:{port}/'
    SHOTS.mkdir(exist_ok=True)
    browser = Browser(W, H)
    try:
        browser.shot(
            url,
            str(SHOTS / 'jackal_all.png'),
            lambda im: (
                count(im, red) > 100 and ROBOT in str(browser.evaluate('document.body.innerText'))
            ),
        )
        text = str(browser.evaluate('document.body.innerText'))
        _switch_off(browser, 'TF')
        shown: Any = browser.shot(
            url=None,
            path=str(SHOTS / 'jackal.png'),
            ready=lambda im: count(im, body, MIDDLE) > 150,
        )
        _switch_off(browser, ROBOT)
        hidden: Any = browser.shot(
            url=None,
            path=str(SHOTS / 'jackal_hidden.png'),
            ready=lambda im: count(im, body, MIDDLE) < 20,
        )
    finally:
        browser.close()
    # the launch file's fixed frame, and the displays zero configuration found
    assert 'fixed frame: odom' in text, text
    assert ROBOT in text and 'LaserScan /front/scan' in text, text
    # the laser sees the course: its hits are drawn, with and without the robot
    assert count(shown, red) > 100 and count(hidden, red) > 100
    # the dark pixels at the centre were the robot model's: switched off, they went
    assert count(shown, body, MIDDLE) > 150 > 20 > count(hidden, body, MIDDLE)
