"""Which types ros2lite can use: its own message/service/action classes, told apart; other
objects refused, and classes generated for rclpy's C type support named as such."""

from __future__ import annotations

from typing import Any

import pytest

from ros2lite.exceptions import NoTypeSupportImportedException
from ros2lite.interfaces import get_interface
from ros2lite.runtime.typesupport_checks import (
    check_for_type_support,
    check_is_valid_action_type,
    check_is_valid_msg_type,
    check_is_valid_srv_type,
)

STRING = get_interface('std_msgs/msg/String')
TRIGGER = get_interface('std_srvs/srv/Trigger')
FIBONACCI = get_interface('action_tutorials_interfaces/action/Fibonacci')


class _RclpyGenerated(type):
    _TYPE_SUPPORT: Any = None

    @classmethod
    def __import_type_support__(cls) -> None:
        pass


class Foreign(metaclass=_RclpyGenerated):
    pass


def test_checks() -> None:
    for ours in (STRING, TRIGGER, FIBONACCI):
        check_for_type_support(ours)
    check_is_valid_msg_type(STRING)
    check_is_valid_srv_type(TRIGGER)
    check_is_valid_action_type(FIBONACCI)
    with pytest.raises(RuntimeError):
        check_is_valid_msg_type(TRIGGER)
    with pytest.raises(RuntimeError):
        check_is_valid_srv_type(STRING)
    with pytest.raises(AttributeError):
        check_for_type_support(object())
    with pytest.raises(NoTypeSupportImportedException, match='generated for rclpy'):
        check_for_type_support(Foreign)
