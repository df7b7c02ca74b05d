"""ros2lite: the ROS 2 command line and a small rclpy-like client library over rmw_zenoh.

Kept import-free so `ros2lite --help` stays fast; the library lives in submodules.
"""

__version__ = '0.1.0'
