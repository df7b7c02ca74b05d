"""ros2lite's teleop_twist_keyboard: the robot-course keyboard driver on `cmd_vel`."""
