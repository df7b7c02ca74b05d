"""ros2lite's take on ROS's lifecycle_py demo: the managed talker `lc_talker`."""
