"""rclpy's serialize_message/deserialize_message over ros2lite's codecs."""

from __future__ import annotations

from ros2lite.interfaces import get_interface
from ros2lite.serialization import deserialize_message, serialize_message


def test_round_trip_and_bytes() -> None:
    pose = get_interface('geometry_msgs/msg/Pose')()
    pose.position.x = 1.5
    data = serialize_message(pose)
    assert data[:4] == b'\x00\x01\x00\x00'  # CDR little endian, as publishers send
    assert deserialize_message(data, type(pose)) == pose
