"""rclpy.time_source."""

from ros2lite.time_source import CLOCK_TOPIC, USE_SIM_TIME_NAME, TimeSource

__all__ = ['CLOCK_TOPIC', 'USE_SIM_TIME_NAME', 'TimeSource']
