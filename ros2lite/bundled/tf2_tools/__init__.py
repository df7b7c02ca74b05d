"""ros2lite's tf2_tools: `view_frames`, the frame tree written as Graphviz text and a PDF."""
