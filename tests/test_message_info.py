"""MessageInfo reads as attributes, and by key as rclpy's info dict does."""

from __future__ import annotations

import pytest

from ros2lite import subscription
from ros2lite.message_info import MessageInfo


def test_fields_read_as_attributes_and_by_key() -> None:
    info = MessageInfo(10, 20, 3, b'\x01' * 16)
    assert info.source_timestamp == 10
    assert info['received_timestamp'] == 20
    assert info.get('publication_sequence_number') == 3
    assert info.get('missing', 'none') == 'none'
    assert info.keys() == [
        'source_timestamp',
        'received_timestamp',
        'publication_sequence_number',
        'publisher_gid',
    ]
    with pytest.raises(KeyError):
        info['missing']


def test_subscriptions_hand_out_the_same_class() -> None:
    assert subscription.MessageInfo is MessageInfo
