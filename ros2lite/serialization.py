"""Messages to CDR bytes and back (rclpy.serialization's names), through the same codecs
publishers and subscriptions use."""

from __future__ import annotations

from typing import Any

from ros2lite.interfaces import deserialize, serialize

__all__ = ['deserialize_message', 'serialize_message']


def serialize_message(message: Any) -> bytes:
    """The CDR bytes (with encapsulation header) a publisher would send for `message`."""
    return serialize(message)


def deserialize_message(serialized_message: bytes, message_type: Any) -> Any:
    """A `message_type` object from CDR bytes."""
    return deserialize(message_type, serialized_message)
