"""rclpy.subscription."""

from ros2lite.subscription import MessageInfo, Subscription

__all__ = ['MessageInfo', 'Subscription']
