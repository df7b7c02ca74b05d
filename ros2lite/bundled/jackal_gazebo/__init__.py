"""jackal_gazebo: the Jackal simulation's launch lines, on ros2lite's 2D world."""
