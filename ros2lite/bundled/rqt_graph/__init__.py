"""ros2lite's rqt_graph: the live node/topic graph in a window, on the terminal, or written
to an SVG or DOT file."""
