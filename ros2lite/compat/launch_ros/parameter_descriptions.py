"""`launch_ros.parameter_descriptions`: typed parameter values and parameter files."""

from ros2lite.launch.ros import ParameterFile, ParameterValue

__all__ = ['ParameterFile', 'ParameterValue']
