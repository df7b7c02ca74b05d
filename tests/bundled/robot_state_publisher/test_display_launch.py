"""Jazzy's URDF tutorial's launch, in its shape (urdf_launch's display included), from a workspace
package: xacro runs through Command, robot_state_publisher gets the URDF, joint_state_publisher
reads it back from /robot_description, and a tf2 Buffer sees every link of the xacro robot."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from ros2lite.tf2 import Buffer, TransformListener
from ros2lite.time import Time
from ros2lite.urdf import parse_urdf
from tests.cli.test_launch import start_launch
from tests.spinning import spin_until
from tests.urdf.robots import bot_workspace, with_display_launch


def test_display_launch_runs_the_model_chain(
    processes: Any, ros_context: Any, tmp_path: Path
) -> None:
    ws = with_display_launch(bot_workspace(tmp_path))
    launch = start_launch(
        processes, 'bot_description', 'display.launch.py', 'gui:=false', 'rviz:=false', cwd=ws
    )
    node = Node('display_probe', context=ros_context)
    descriptions: list[str] = []
    latched = QoSProfile(
        depth=1,
        reliability=ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL,
    )
    node.create_subscription(
        String, '/robot_description', lambda m: descriptions.append(m.data), latched
    )
    buffer = Buffer(node=node)
    listener = TransformListener(buffer, node)
    executor = SingleThreadedExecutor(context=node.context)
    executor.add_node(node)
    try:
        spin_until(executor, lambda: descriptions, timeout=40)
        robot = parse_urdf(descriptions[0])  # what xacro made of the file
        assert robot.name == 'bot' and set(robot.links) == {
            'base_link',
            'left_wheel',
            'right_wheel',
        }
        # the wheels are continuous joints: only joint_state_publisher's states place them
        spin_until(
            executor,
            lambda: all(
                buffer.can_transform('base_link', w, Time()) for w in ('left_wheel', 'right_wheel')
            ),
            timeout=20,
        )
        right = buffer.lookup_transform('base_link', 'right_wheel', Time()).transform.translation
        assert (right.x, right.y, right.z) == (0.0, -0.1, 0.0)
    finally:
        listener.unregister()
        executor.shutdown()
        node.destroy_node()
    assert launch.interrupt() == 0
    text = '\n'.join(launch.lines)
    assert '[robot_state_publisher-1]' in text and 'Robot initialized' in text
    assert 'joint_state_publisher-2' in text and 'rviz2' not in text
