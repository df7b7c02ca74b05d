"""`launch_ros`, as ROS launch files import it: ros2lite's ROS launch actions under
launch_ros's names (names only; the code is in ros2lite.launch.ros)."""

from . import actions, parameter_descriptions, substitutions

__all__ = ['actions', 'parameter_descriptions', 'substitutions']
