"""`launch_ros.substitutions`: finding packages (source workspaces included)."""

from ros2lite.launch.ros import FindPackagePrefix, FindPackageShare

__all__ = ['FindPackagePrefix', 'FindPackageShare']
