"""turtlebot3_gazebo: the TurtleBot3 simulation's launch lines, on ros2lite's 2D world."""
