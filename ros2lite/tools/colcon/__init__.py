"""ros2lite's colcon plugin: `colcon build` of a ROS workspace with no ROS install.

colcon (`pip install 'ros2lite[colcon]'`) loads :mod:`.extensions` through its entry points.
Interface packages are checked (:mod:`.rosidl`) and installed from what their CMakeLists.txt
says (:mod:`.cmake`); C++ packages are named in one line and passed over. Nothing here is
imported by ros2lite's own commands.
"""
