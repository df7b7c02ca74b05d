"""ros2lite's rqt_tf_tree: the live tf frame tree in a window or on the terminal."""
