"""A small frame tree on the wire, for the frame tools' tests: `world -> turtle1 -> carrot1`
moving at 20 Hz and a static `world -> turtle2`, from a node in a process of its own."""

from __future__ import annotations

from typing import Any

BROADCASTER = r'''
import ros2lite
from ros2lite.executors import ExternalShutdownException
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.node import Node
from ros2lite.tf2 import StaticTransformBroadcaster, TransformBroadcaster

def transform(node, parent, child, x):
    t = TransformStamped()
    t.header.stamp = node.get_clock().now().to_msg()
    t.header.frame_id = parent
    t.child_frame_id = child
    t.transform.translation.x = x
    t.transform.rotation.w = 1.0
    return t

with ros2lite.init():
    node = Node('turtle_tf2_broadcaster')
    static = StaticTransformBroadcaster(node)
    static.sendTransform(transform(node, 'world', 'turtle2', 4.0))
    moving = TransformBroadcaster(node)
    node.create_timer(0.05, lambda: moving.sendTransform(
        [transform(node, 'world', 'turtle1', 1.0), transform(node, 'turtle1', 'carrot1', 0.5)]))
    print('broadcasting', flush=True)
    try:
        ros2lite.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
'''
FRAMES = ('world', 'turtle1', 'turtle2', 'carrot1')


def start_broadcaster(processes: Any) -> Any:
    """The broadcasting process, once its node is up."""
    proc = processes.python(BROADCASTER)
    assert proc.stdout.readline() == 'broadcasting\n', proc.stderr.read()
    return proc
