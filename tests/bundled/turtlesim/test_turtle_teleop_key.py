"""`turtle_teleop_key` driven through a pseudo-terminal against a real turtlesim: arrows move
turtle1, the letter keys rotate it, F cancels, Q quits; the terminal is restored on every
way out (Q, Ctrl-C, SIGTERM)."""

from __future__ import annotations

import math
import signal
import termios
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from tests.bundled.ptyproc import PtyProcess, ros2lite_argv
from tests.bundled.turtlesim.conftest import wait_for_log
from tests.bundled.turtlesim.test_node import pose, settle
from tests.cli.conftest import Result

INSTRUCTIONS = (
    'Reading from keyboard\r\n'
    '---------------------------\r\n'
    'Use arrow keys to move the turtle.\r\n'
    "Use g|b|v|c|d|e|r|t keys to rotate to absolute orientations. 'f' to cancel a rotation.\r\n"
    "'q' to quit."
)


@pytest.fixture
def teleop() -> Iterator[Callable[[], PtyProcess]]:
    started: list[PtyProcess] = []

    def start() -> PtyProcess:
        proc = PtyProcess(ros2lite_argv('run', 'turtlesim', 'turtle_teleop_key'))
        started.append(proc)
        proc.expect("'q' to quit.")
        return proc

    yield start
    for proc in started:
        proc.close()


def changed_lflag(proc: PtyProcess) -> int:
    return int(proc.attrs()[3])


def test_drive_rotate_cancel_quit(
    run: Callable[..., Result], turtlesim: Any, teleop: Callable[[], PtyProcess]
) -> None:
    sim_proc, lines = turtlesim
    proc = teleop()
    assert INSTRUCTIONS in proc.output
    lflag = changed_lflag(proc)
    assert not lflag & termios.ECHO and not lflag & termios.ICANON  # keys arrive one by one

    p0 = pose(run)
    proc.send('\x1b[A')  # up: 2.0 m/s for a second
    p = settle(run, moved_from=p0)
    assert 1.95 < p['x'] - p0['x'] < 2.05 and abs(p['theta']) < 1e-6  # 62 or 63 steps
    proc.send('\x1b[D')  # left: 2.0 rad/s for a second (62 steps, turned about 1.98 rad)
    p = settle(run, moved_from=p)
    assert abs(p['theta'] - 62 * 0.016 * 2.0) < 0.04

    proc.send('r')  # rotate to pi/2
    wait_for_log(sim_proc, lines, r'\[turtlesim\]: Rotation goal completed successfully$')
    assert abs(pose(run)['theta'] - math.pi / 2) < 0.02

    proc.send('d')  # towards pi (1.57 rad away: about 1.6 s)...
    time.sleep(0.5)
    proc.send('f')  # ...canceled on the way
    wait_for_log(sim_proc, lines, r'\[turtlesim\]: Rotation goal canceled$')
    theta = settle(run)['theta']
    assert math.pi / 2 + 0.1 < theta < math.pi - 0.1

    proc.send('Q')
    assert proc.wait() == 0
    lflag = changed_lflag(proc)
    assert lflag & termios.ECHO and lflag & termios.ICANON  # given back as it was


@pytest.mark.parametrize('how', ['ctrl-c', 'sigterm'])
def test_terminal_restored_when_stopped(
    ros_router: str, teleop: Callable[[], PtyProcess], how: str
) -> None:
    proc = teleop()
    before = proc.attrs()
    assert not before[3] & termios.ECHO
    if how == 'ctrl-c':
        proc.send('\x03')  # the terminal's interrupt key: SIGINT to its foreground group
    else:
        import os

        # the launcher forwards SIGTERM to the node, which must still restore the terminal
        os.kill(proc.pid, signal.SIGTERM)
    code = proc.wait()
    assert code in (0, 128 + signal.SIGTERM, -signal.SIGTERM), proc.output
    lflag = changed_lflag(proc)
    assert lflag & termios.ECHO and lflag & termios.ICANON, proc.output
    assert 'Traceback' not in proc.output
