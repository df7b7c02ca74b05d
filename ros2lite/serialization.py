"""Messages to CDR bytes and back (rclpy.serialization's names), through the same codecs
publishers and subscriptions use."""

from __future__ import annotations

from typing import TYPE_CHECKING, cast

from ros2lite.interfaces import deserialize, serialize
from ros2lite.type_support import MsgT

if TYPE_CHECKING:
    from ros2lite.interfaces import Message
    from ros2lite.type_support import Msg

__all__ = ['deserialize_message', 'serialize_message']


def serialize_message(message: Msg) -> bytes:
    """The CDR bytes (with encapsulation header) a publisher would send for `message`."""
    return serialize(message)


def deserialize_message(serialized_message: bytes, message_type: type[MsgT]) -> MsgT:
    """A `message_type` object from CDR bytes."""
    return cast(MsgT, deserialize(cast('type[Message]', message_type), serialized_message))
