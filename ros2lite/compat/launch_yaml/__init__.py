"""`launch_yaml`: YAML launch files (read by ros2lite.launch.frontend)."""

from . import launch_description_sources

__all__ = ['launch_description_sources']
