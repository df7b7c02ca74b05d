"""`ament_copyright`, as the tests `ros2 pkg create` writes import it (`ament_copyright.main`):
ROS's copyright and licence checker has no wheel on PyPI, so ros2lite carries one. It is on
PYTHONPATH in a ROS shell (`ros2lite env`) and in `colcon test` through ros2lite's plugin."""
