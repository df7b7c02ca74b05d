"""Robot descriptions: URDF text (after xacro) to immutable values, the kinematics
robot_state_publisher needs (`ros2lite.urdf.kinematics`), and resource URIs (meshes,
textures) resolved through the package index, confined to package share folders."""

from ros2lite.urdf.errors import ResourceNotFoundError, UrdfError
from ros2lite.urdf.model import Geometry, Joint, Link, Mimic, Robot, Visual
from ros2lite.urdf.parse import parse_urdf
from ros2lite.urdf.resources import resolve_resource

__all__ = [
    'Geometry',
    'Joint',
    'Link',
    'Mimic',
    'ResourceNotFoundError',
    'Robot',
    'UrdfError',
    'Visual',
    'parse_urdf',
    'resolve_resource',
]
