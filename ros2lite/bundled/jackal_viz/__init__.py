"""jackal_viz: the Jackal's view launch line, opening ros2lite's rviz2 (the browser view)."""
