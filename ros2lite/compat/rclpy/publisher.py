"""rclpy.publisher."""

from ros2lite.publisher import Publisher

__all__ = ['Publisher']
