"""turtlesim's window under a virtual X display, checked on a screenshot as a person would
see it: the background colour (live with `param set`), a pen trail, the turtle, and /clear."""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from typing import Any

from tests.bundled.screenshot import Image, screenshot
from tests.bundled.turtlesim.conftest import start_turtlesim
from tests.cli.conftest import Result

BACKGROUND = (69, 86, 255)
RED = (255, 0, 0)


def wait_for_shot(display: str, ok: Callable[[Image], bool]) -> Image:
    """The first screenshot (within 15 s) for which `ok(shot)` holds."""
    deadline = time.monotonic() + 15
    while True:
        shot = screenshot(display)
        if ok(shot):
            return shot
        assert time.monotonic() < deadline, 'the window never showed it'
        time.sleep(0.2)


def wait_for_pixel(display: str, x: int, y: int, colour: tuple[int, int, int]) -> Image:
    return wait_for_shot(display, lambda shot: shot.pixel(x, y) == colour)


def test_window_shows_background_trail_and_turtle(
    run: Callable[..., Result], processes: Any, xdisplay: str, tmp_path: Any
) -> None:
    os.environ['DISPLAY'] = xdisplay  # for the node process (auto picks the window)
    try:
        proc, _ = start_turtlesim(processes)
    finally:
        del os.environ['DISPLAY']
    # the whole 500x500 canvas in the background colour, turtle1 at its centre
    shot = wait_for_pixel(xdisplay, 10, 10, BACKGROUND)
    assert shot.count(BACKGROUND, (0, 0, 500, 500)) > 0.99 * 500 * 500
    assert shot.pixel(249, 249) != BACKGROUND  # the turtle's shell

    # a 5 px red trail from the centre to x = 2 m (pixel 90), drawn by a teleport
    run('service', 'call', '/turtle1/set_pen', 'turtlesim/srv/SetPen',
        '{r: 255, g: 0, b: 0, width: 5}')  # fmt: skip
    run('service', 'call', '/turtle1/teleport_absolute', 'turtlesim/srv/TeleportAbsolute',
        '{x: 2.0, y: 5.544445, theta: 0.0}')  # fmt: skip
    wait_for_pixel(xdisplay, 170, 250, RED)

    def moved(shot: Image) -> bool:  # the turtle drawn at the trail's end, over it
        return shot.pixel(90, 249) not in (BACKGROUND, RED)

    # the trail and the moved turtle can reach the screen in two redraws (a loaded run
    # caught the one between): the shot is taken once both are there
    shot = wait_for_shot(xdisplay, moved)
    shot.save_png(str(tmp_path / 'turtlesim.png'))
    assert shot.count(RED, (120, 240, 220, 260)) == 100 * 5  # 5 px thick, 100 px long
    assert shot.pixel(170, 262) == BACKGROUND

    # the background parameter, applied live; the trail stays on top
    run('param', 'set', '/turtlesim', 'background_r', '150')
    shot = wait_for_pixel(xdisplay, 400, 100, (150, 86, 255))
    assert shot.pixel(170, 250) == RED

    run('service', 'call', '/clear', 'std_srvs/srv/Empty')
    shot = wait_for_pixel(xdisplay, 170, 250, (150, 86, 255))

    processes.stop(proc)
    assert proc.returncode == 0
