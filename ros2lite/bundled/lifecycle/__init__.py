"""ros2lite's take on ROS's lifecycle demo package: the listener that watches `lc_talker`."""
