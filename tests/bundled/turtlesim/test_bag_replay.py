"""The lesson's bag exercise: record /turtle1/cmd_vel while driving, reset, play the bag
back, and the turtle ends where it ended before."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

from ros2lite.msgs.geometry_msgs.msg import Twist
from ros2lite.node import Node
from tests.bundled.turtlesim.test_node import settle
from tests.cli.conftest import Result, run_process


def test_recorded_drive_replays_to_the_same_pose(
    run: Callable[..., Result], turtlesim: Any, processes: Any, ros_context: Any, tmp_path: Any
) -> None:
    bag = tmp_path / 'drive'
    recorder = processes.cli('bag', 'record', '--topics', '/turtle1/cmd_vel', '-o', str(bag))
    driver = Node('teleop_turtle', context=ros_context)
    pub = driver.create_publisher(Twist, 'turtle1/cmd_vel', 10)
    deadline = time.monotonic() + 15
    while pub.get_subscription_count() < 2:  # turtlesim and the recorder
        assert time.monotonic() < deadline
        time.sleep(0.05)
    for linear, angular in ((1.5, 0.0), (0.5, 1.2), (1.0, -0.8), (0.8, 0.0)):
        twist = Twist()
        twist.linear.x = linear
        twist.angular.z = angular
        pub.publish(twist)
        time.sleep(0.4)
    before = settle(run)
    processes.stop(recorder, timeout=15)
    assert recorder.returncode == 0
    driver.destroy_node()

    run('service', 'call', '/reset', 'std_srvs/srv/Empty')
    start = settle(run)
    assert (start['x'], start['theta']) == (5.544444561004639, 0.0)
    played = run_process('bag', 'play', str(bag))
    assert played.code == 0, played.err
    after = settle(run, moved_from=start)
    assert math.dist((after['x'], after['y']), (before['x'], before['y'])) < 0.1, (before, after)
    assert abs(after['theta'] - before['theta']) < 0.05
