"""rclpy.type_support."""

from ros2lite.runtime.typesupport_checks import (
    check_for_type_support,
    check_is_valid_action_type,
    check_is_valid_msg_type,
    check_is_valid_srv_type,
)

__all__ = [
    'check_for_type_support',
    'check_is_valid_action_type',
    'check_is_valid_msg_type',
    'check_is_valid_srv_type',
]
