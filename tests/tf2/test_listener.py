"""Listener and broadcasters over a real router: /tf reaches a listening buffer, /tf_static
sent before the listener existed still arrives (transient local), tf2's QoS on the wire,
the buffer's tf2_frames service and a listener with its own spinning thread."""

from __future__ import annotations

from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.msgs.tf2_msgs.srv import FrameGraph
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy
from ros2lite.tf2 import (
    Buffer,
    StaticTransformBroadcaster,
    TransformBroadcaster,
    TransformListener,
)
from ros2lite.time import Time
from tests.spinning import spin_until, wait_until


def stamped(parent: str, child: str, sec: int, x: float) -> TransformStamped:
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id = parent, child
    t.header.stamp.sec = sec
    t.transform.translation.x = x
    return t


def test_static_before_listener_and_dynamic_after(ros_context: Any) -> None:
    sender = Node('tf_sender', context=ros_context)
    static = StaticTransformBroadcaster(sender)
    static.sendTransform(stamped('world', 'table', 0, 1.0))
    static.sendTransform([stamped('table', 'cup', 0, 0.5), stamped('world', 'table', 0, 2.0)])
    assert [t.child_frame_id for t in static.net_message.transforms] == ['table', 'cup']
    dynamic = TransformBroadcaster(sender)
    receiver = Node('tf_receiver', context=ros_context)
    buffer = Buffer(node=receiver)
    listener = TransformListener(buffer, receiver)
    subs = {s.topic_name: s.qos_profile for s in (listener.tf_sub, listener.tf_static_sub)}
    assert subs['/tf_static'].durability == DurabilityPolicy.TRANSIENT_LOCAL
    assert (subs['/tf_static'].depth, subs['/tf'].depth) == (100, 100)
    assert subs['/tf'].durability == DurabilityPolicy.VOLATILE
    assert static.pub_tf.qos_profile.durability == DurabilityPolicy.TRANSIENT_LOCAL
    assert static.pub_tf.qos_profile.depth == 1
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(sender)
    executor.add_node(receiver)

    # the static message was published before the listener existed: history brings it
    spin_until(executor, lambda: buffer.can_transform('world', 'cup', Time()), timeout=10)
    got = buffer.lookup_transform('world', 'cup', Time())
    assert got.transform.translation.x == 2.5  # the replaced table, then the cup on it

    def send() -> None:  # /tf is volatile: sent again until the subscription matches
        dynamic.sendTransform(stamped('cup', 'spoon', 7, 0.25))
        executor.spin_once(timeout_sec=0.05)

    wait_until(lambda: buffer.can_transform('world', 'spoon', Time()), step=send)
    assert buffer.lookup_transform('world', 'spoon', Time()).transform.translation.x == 2.75
    assert 'spoon: \n  parent: \'cup\'\n  broadcaster: \'default_authority\'' in (
        buffer.all_frames_as_yaml()
    )
    # the buffer's service hands the same YAML to tools (view_frames)
    client = sender.create_client(FrameGraph, 'tf2_frames')
    spin_until(executor, client.service_is_ready, timeout=10)
    future = client.call_async(FrameGraph.Request())
    spin_until(executor, future.done, timeout=10)
    assert "cup: \n  parent: 'table'" in future.result().frame_yaml
    listener.unregister()
    executor.shutdown()


def test_listener_with_its_own_thread(ros_context: Any) -> None:
    sender = Node('tf_sender2', context=ros_context)
    StaticTransformBroadcaster(sender).sendTransform(stamped('map', 'odom', 0, 3.0))
    user = Node('tf_user', context=ros_context)  # never spun by anyone
    buffer = Buffer()
    listener = TransformListener(buffer, user, spin_thread=True)
    try:
        got = buffer.lookup_transform('map', 'odom', Time(), timeout=_seconds(20))
        assert got.transform.translation.x == 3.0
    finally:
        listener.unregister()
    assert listener.dedicated_listener_thread is not None
    assert not listener.dedicated_listener_thread.is_alive()


def _seconds(s: float) -> Any:
    from ros2lite.duration import Duration

    return Duration(seconds=s)
