"""ros2lite's take on ROS's demo_nodes_py: `talker` and `listener` on `chatter`."""
