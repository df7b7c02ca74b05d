"""rclpy.waitable."""

from ros2lite.waitable import NumberOfEntities, Waitable

__all__ = ['NumberOfEntities', 'Waitable']
