"""rclpy.impl: rclpy's implementation details that user code reaches (loggers, severities).
rclpy's C extension (``implementation_singleton``) has no counterpart: ros2lite has none."""
