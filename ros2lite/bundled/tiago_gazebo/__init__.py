"""tiago_gazebo: PAL's TIAGo simulation launch file (what br2_tiago's sim.launch.py
includes), on ros2lite's 2D world."""
