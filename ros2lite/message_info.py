"""What a subscription callback may get beside the message: the sample's delivery metadata.

Its own module, below the subscriptions and the delivery loops that both hand it out
(ros2lite.subscription re-exports it, as rclpy users import it from there).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ['MessageInfo']


@dataclass(frozen=True)
class MessageInfo:
    """Delivery metadata from the rmw_zenoh attachment, plus our receive time. Readable as
    attributes, or by key as rclpy's dict is (`info['source_timestamp']`)."""

    source_timestamp: int  # ns since the epoch, from the publisher
    received_timestamp: int  # ns since the epoch, when the sample arrived here
    publication_sequence_number: int
    publisher_gid: bytes

    def __getitem__(self, key: str) -> int | bytes:
        try:
            return getattr(self, key)
        except AttributeError:
            raise KeyError(key) from None

    def get(self, key: str, default: object = None) -> object:
        """A field by name, or `default` (rclpy's info is a dict)."""
        return getattr(self, key, default)

    def keys(self) -> list[str]:
        """The field names, as the keys of rclpy's info dict."""
        return list(self.__dataclass_fields__)
