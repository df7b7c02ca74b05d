"""`launch_yaml.launch_description_sources`: including a YAML launch file."""

from ros2lite.launch.sources import YAMLLaunchDescriptionSource

__all__ = ['YAMLLaunchDescriptionSource']
