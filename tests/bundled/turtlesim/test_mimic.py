"""`mimic` pairs two turtles: turtle2 copies turtle1's velocities through remapped topics."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from tests.bundled.turtlesim.test_node import pose, settle, wait_for
from tests.cli.conftest import Result


def test_turtle2_follows_turtle1(
    run: Callable[..., Result], turtlesim: Any, processes: Any
) -> None:
    run('service', 'call', '/spawn', 'turtlesim/srv/Spawn', '{x: 2.0, y: 2.0}')
    proc = processes.cli(
        'run', 'turtlesim', 'mimic', '--ros-args',
        '-r', 'input/pose:=/turtle1/pose', '-r', 'output/cmd_vel:=/turtle2/cmd_vel',
    )  # fmt: skip
    # the node's endpoints, under their remapped names
    wait_for(run, ('node', 'info', '/turtle_mimic'), '    /turtle1/pose: turtlesim/msg/Pose', True)
    wait_for(
        run,
        ('node', 'info', '/turtle_mimic'),
        '    /turtle2/cmd_vel: geometry_msgs/msg/Twist',
        True,
    )
    deadline = time.monotonic() + 10
    while run('topic', 'info', '/turtle1/pose').out.count('Subscription count: 1') != 1:
        assert time.monotonic() < deadline
        time.sleep(0.1)
    start = pose(run, 'turtle2')
    leader = pose(run, 'turtle1')
    run('topic', 'pub', '--once', '-w', '1', '/turtle1/cmd_vel', 'geometry_msgs/msg/Twist',
        '{linear: {x: 1.0}, angular: {z: 0.5}}')  # fmt: skip
    settle(run, 'turtle1', moved_from=leader)
    end = settle(run, 'turtle2', moved_from=start)
    # the same arc from its own start: about 1 m travelled, turned about 0.5 rad
    assert 0.85 < ((end['x'] - start['x']) ** 2 + (end['y'] - start['y']) ** 2) ** 0.5 < 1.05
    assert 0.4 < end['theta'] - start['theta'] < 0.55
    processes.stop(proc)
