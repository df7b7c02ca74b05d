"""`launch_ros.actions`: Node and the scoped ROS settings."""

from ros2lite.launch.ros import (
    Node,
    PushRosNamespace,
    SetParameter,
    SetParametersFromFile,
    SetRemap,
)

PushROSNamespace = PushRosNamespace  # the spelling newer launch_ros uses

__all__ = [
    'Node',
    'PushROSNamespace',
    'PushRosNamespace',
    'SetParameter',
    'SetParametersFromFile',
    'SetRemap',
]
