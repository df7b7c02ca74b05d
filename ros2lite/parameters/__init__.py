"""Per-node parameters: the store (rules), its node API, the services, events and files.

`ros2lite.parameter` holds the `Parameter` type itself (rclpy's module path).
"""
