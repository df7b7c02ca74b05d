"""rviz2: the robot's scene, in a browser, a window or on the terminal."""
