"""ros2lite's rqt_console: the live `/rosout` log in a window or a terminal table."""
