"""turtle_tf2_py: turtlesim's tf2 demo (each turtle's pose broadcast as a frame, and a
listener that makes turtle2 follow turtle1)."""
