"""joint_state_publisher_gui: joint_state_publisher with a window of sliders, one for each
free joint of the robot."""
