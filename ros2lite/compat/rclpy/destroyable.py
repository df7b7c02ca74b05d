"""rclpy.destroyable."""

from ros2lite.destroyable import DestroyableType

__all__ = ['DestroyableType']
