"""ros2lite's turtlesim: the simulation (`sim`), the `/turtlesim` node, its views (a tkinter
window, a terminal canvas) and the tutorial executables (teleop, draw_square, mimic)."""
